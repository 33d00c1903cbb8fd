//! The `lucid` command line on the machine's device (lavapipe in CI): listings, headless renders of
//! each algorithm and denoiser, and clear one-line errors with a non-zero exit for bad input.

use std::path::Path;
use std::process::Command;

mod run_lucid;
use run_lucid::{lucid, stderr, temp};

#[test]
fn scenes_lists_every_builtin_scene() {
    let out = lucid(&["scenes", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let listed: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let names: Vec<&str> = listed
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    for name in lucid_engine::scene::builtin::names() {
        assert!(names.contains(name), "{name} missing from {names:?}");
    }
    let covered = listed
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "covered-light")
        .unwrap();
    assert!(covered["triangles"].as_u64().unwrap() >= 5_000_000);
}

#[test]
fn renders_each_algorithm_and_denoiser_at_64x64() {
    for (algo, denoise) in [
        ("pt", "none"),
        ("bdpt", "none"),
        ("pt", "svgf"),
        ("pt", "neural"),
    ] {
        let file = temp(&format!("{algo}-{denoise}.png"));
        let out = lucid(&[
            "render",
            "--scene",
            "cornell-box",
            "--algo",
            algo,
            "--denoise",
            denoise,
            "--size",
            "64x64",
            "--spp",
            "2",
            "--frames",
            "2",
            "--out",
            file.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{algo}/{denoise}: {}", stderr(&out));
        assert!(
            !stderr(&out).contains("VUID"),
            "validation messages: {}",
            stderr(&out)
        );
        let image = lucid_engine::capture::load(&file).unwrap();
        assert_eq!((image.width, image.height), (64, 64));
        let mean = image.mean_rgb();
        assert!(
            mean[0] > 0.05 && mean[0] < 0.95,
            "{algo}/{denoise}: a lit image, mean {mean:?}"
        );
        std::fs::remove_file(&file).unwrap();
    }
    let exr = temp("hdr.exr");
    let out = lucid(&[
        "render",
        "--size",
        "32x32",
        "--frames",
        "1",
        "--out",
        exr.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        lucid_engine::capture::load(&exr)
            .unwrap()
            .pixels
            .iter()
            .any(|p| p[0] > 1.0),
        "HDR values survive in EXR"
    );
    std::fs::remove_file(&exr).unwrap();
}

fn assert_clear_failure(args: &[&str], expect: &str) {
    let out = lucid(args);
    let err = stderr(&out);
    assert!(!out.status.success(), "{args:?} must fail");
    assert!(
        err.contains(expect),
        "{args:?}: expected {expect:?} in {err:?}"
    );
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
}

/// `lucid` without a subcommand takes the options of `lucid view`: with no display to open the
/// window on, it gets as far as saying so.
#[test]
fn the_sandbox_takes_its_options_without_a_subcommand() {
    let shot = temp("shot.png");
    let out = Command::new(env!("CARGO_BIN_EXE_lucid"))
        .args(["--screenshot-after", "20", shot.to_str().unwrap()])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run lucid");
    let err = stderr(&out);
    assert!(!out.status.success(), "no display: {err}");
    assert!(err.contains("no display found"), "{err}");
    assert!(!shot.exists());
}

#[test]
fn bad_arguments_and_files_fail_with_a_clear_message() {
    assert_clear_failure(
        &["render", "--scene", "no-such-scene", "--size", "8x8"],
        "no-such-scene",
    );
    assert_clear_failure(&["render", "--size", "0x8"], "0x8");
    assert_clear_failure(
        &["render", "--out", "image.jpg", "--size", "8x8"],
        ".png or .exr",
    );
    assert_clear_failure(&["render", "--algo", "vcm"], "vcm");
    assert_clear_failure(
        &["render", "--scene", "/nonexistent/scene.glb"],
        "does not exist",
    );
    let broken = temp("broken.gltf");
    std::fs::write(&broken, br#"{"asset": {"version": "2.0"}, "meshes": [ {"primitives": [ {"attributes": {"POSITION": 7}} ]} ]"#).unwrap();
    assert_clear_failure(
        &[
            "render",
            "--scene",
            broken.to_str().unwrap(),
            "--size",
            "8x8",
        ],
        "broken.gltf",
    );
    std::fs::remove_file(&broken).unwrap();
}

#[test]
fn bench_reports_pipeline_statistics_or_says_they_are_unavailable() {
    let json = temp("bench-stats.json");
    let out = lucid(&[
        "bench",
        "--scene",
        "cornell-box",
        "--size",
        "64x64",
        "--spp",
        "1",
        "--frames",
        "2",
        "--warmup",
        "1",
        "--pipeline-statistics",
        "--json",
        json.to_str().unwrap(),
    ]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains("VUID"), "validation messages: {err}");
    let report: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    std::fs::remove_file(&json).unwrap();
    match &report["pipelines"] {
        serde_json::Value::Null => assert!(err.contains("none captured"), "{err}"),
        serde_json::Value::Object(pipelines) => {
            assert!(!pipelines.is_empty(), "{report}");
            assert!(
                pipelines.values().all(|s| s.as_object().is_some()),
                "{report}"
            );
            assert!(err.contains("pipeline statistics ("), "{err}");
        }
        other => panic!("\"pipelines\" must be null or an object, got {other}"),
    }
}

#[test]
fn bench_times_passes_that_share_a_name_as_their_sum() {
    // SVGF's five a-trous iterations are passes named `svgf.atrous`: each frame's entry is their
    // sum, so the passes' means add up to the frame's mean (an iteration's time alone would not).
    let json = temp("bench-svgf.json");
    let out = lucid(&[
        "bench",
        "--scene",
        "cornell-box",
        "--denoise",
        "svgf",
        "--size",
        "32x32",
        "--frames",
        "3",
        "--warmup",
        "1",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    std::fs::remove_file(&json).unwrap();
    let passes = report["passes_ms"].as_object().expect("passes_ms");
    assert!(passes.contains_key("svgf.atrous"), "{report}");
    let sum: f64 = passes.values().map(|p| p["mean"].as_f64().unwrap()).sum();
    let frame = report["frame_ms"]["mean"].as_f64().unwrap();
    assert!(
        (sum - frame).abs() <= 1e-6 * frame.max(1.0),
        "the passes' means add up to {sum} ms, the frame's mean is {frame} ms"
    );
}

#[test]
fn bench_reports_every_frames_image_time() {
    // Each timed frame's HDR image time, in order, for transients the summary hides.
    let report = short_bench_report(&temp("bench-per-frame.json"), "cornell-box", "none", &[]);
    let per_frame: Vec<f64> = report["image_ms_per_frame"]
        .as_array()
        .expect("image_ms_per_frame")
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(per_frame.len(), 2, "{report}");
    let mean = per_frame.iter().sum::<f64>() / 2.0;
    let image = report["image_ms"]["mean"].as_f64().unwrap();
    assert!(
        (mean - image).abs() <= 1e-9 * image.max(1.0),
        "{mean} against {image}"
    );
}

#[test]
fn bench_reports_the_image_span_with_the_gaps_between_passes() {
    // From the first pass's start to the last image pass's end: at least the passes' own times
    // (they run one after another), at most the wall time of a frame (each is waited for).
    let report = short_bench_report(&temp("bench-span.json"), "cornell-box", "svgf", &[]);
    let span = report["image_span_ms"]["mean"]
        .as_f64()
        .expect("image_span_ms");
    let image = report["image_ms"]["mean"].as_f64().unwrap();
    let wall_ms = 1e3 / report["wall_fps"].as_f64().unwrap();
    assert!(
        span >= image * (1.0 - 1e-9),
        "span {span} against the passes' {image}"
    );
    assert!(
        span <= wall_ms,
        "span {span} against {wall_ms} ms of wall time a frame"
    );
}

/// Runs a short 32x32 `lucid bench` of `scene` with `denoiser` and the `extra` options, its JSON
/// report written to `json`.
fn short_bench(
    json: &std::path::Path,
    scene: &str,
    denoiser: &str,
    extra: &[&str],
) -> std::process::Output {
    let mut args = vec![
        "bench",
        "--scene",
        scene,
        "--denoise",
        denoiser,
        "--size",
        "32x32",
        "--frames",
        "2",
        "--warmup",
        "1",
        "--json",
        json.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    lucid(&args)
}

/// The JSON report of a [`short_bench`] that must succeed (the file is removed).
fn short_bench_report(
    json: &std::path::Path,
    scene: &str,
    denoiser: &str,
    extra: &[&str],
) -> serde_json::Value {
    let out = short_bench(json, scene, denoiser, extra);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = serde_json::from_slice(&std::fs::read(json).unwrap()).unwrap();
    std::fs::remove_file(json).unwrap();
    report
}

/// The edge pass runs for the learned denoiser unless `--edge-emission off`, for SVGF only with
/// `--edge-emission` (alone: `on`); the report says whether it ran and times it.
#[test]
fn bench_with_edge_emission_times_its_pass_and_says_so() {
    let json = temp("bench-edge-emission.json");
    let cases: [(&str, &[&str], bool); 4] = [
        ("neural", &[], true),
        ("neural", &["--edge-emission", "off"], false),
        ("svgf", &[], false),
        ("svgf", &["--edge-emission"], true),
    ];
    for (denoiser, edge, ran) in cases {
        let report = short_bench_report(&json, "cornell-box", denoiser, edge);
        assert_eq!(
            report["edge_emission"], ran,
            "{denoiser} {edge:?}: {report}"
        );
        let passes = report["passes_ms"].as_object().expect("passes_ms");
        assert_eq!(passes.contains_key("edge_emission"), ran, "{report}");
    }
}

/// The learned denoiser's gated filter runs unless `--neural-filter off`; the report says whether
/// and times its steps; a value that is neither on nor off is refused, naming the option, by
/// `bench` and by `view` (before any window opens).
#[test]
fn bench_runs_the_neural_gated_filter_unless_turned_off() {
    let json = temp("bench-neural-filter.json");
    for (filter, on) in [(&[][..], true), (&["--neural-filter", "off"][..], false)] {
        let report = short_bench_report(&json, "cornell-box", "neural", filter);
        assert_eq!(report["neural_gated_filter"], on, "{filter:?}: {report}");
        let passes = report["passes_ms"].as_object().expect("passes_ms");
        let steps = passes.keys().filter(|k| k.contains(".atrous")).count();
        assert_eq!(steps, if on { 2 } else { 0 }, "{filter:?}: {report}");
    }
    let sometimes = ["--neural-filter", "sometimes"];
    let bench = short_bench(&json, "cornell-box", "neural", &sometimes);
    let view = lucid(&["view", "--denoise", "neural", sometimes[0], sometimes[1]]);
    for out in [bench, view] {
        assert!(!out.status.success(), "{sometimes:?} was accepted");
        let message = stderr(&out);
        assert!(
            message.contains("invalid value") && message.contains("--neural-filter"),
            "{message}"
        );
    }
}

/// SVGF's firefly clamp is on unless `--svgf-firefly-clamp off`, with the headroom
/// `--svgf-firefly-headroom` gives; the report says both; a value that is neither on nor off, or a
/// headroom below 1, is an error naming the option.
#[test]
fn bench_reports_the_svgf_firefly_clamp() {
    let json = temp("bench-firefly-clamp.json");
    for (clamp, on, headroom) in [
        (&[][..], true, 32.0),
        (&["--svgf-firefly-clamp", "off"][..], false, 32.0),
        (&["--svgf-firefly-headroom", "4"][..], true, 4.0),
    ] {
        let report = short_bench_report(&json, "caustics", "svgf", clamp);
        assert_eq!(report["svgf_firefly_clamp"], on, "{clamp:?}: {report}");
        assert_eq!(
            report["svgf_firefly_headroom"], headroom,
            "{clamp:?}: {report}"
        );
    }
    for (option, value) in [
        ("--svgf-firefly-clamp", "sometimes"),
        ("--svgf-firefly-headroom", "0.5"),
    ] {
        let out = short_bench(&json, "caustics", "svgf", &[option, value]);
        assert!(!out.status.success(), "{option} {value} was accepted");
        assert!(stderr(&out).contains(option), "{}", stderr(&out));
    }
}

#[test]
fn a_short_soak_keeps_memory_flat_without_validation_messages() {
    // 200 frames through every algorithm and denoiser (12 configurations of 5 frames: three cycles;
    // every other one with the edge pass and without the learned denoiser's gated filter), the
    // camera and an object moving.
    let out = lucid(&[
        "soak",
        "--frames",
        "200",
        "--size",
        "32x32",
        "--switch-every",
        "5",
        "--sample-every",
        "5",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(String::from_utf8_lossy(&out.stdout).contains("flat:"));
}

#[test]
fn a_soak_too_short_to_compare_memory_is_an_error() {
    let out = lucid(&[
        "soak",
        "--frames",
        "20",
        "--size",
        "16x16",
        "--switch-every",
        "5",
    ]);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("no two memory samples"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn the_learned_denoiser_takes_weights_from_a_file_and_names_a_bad_one() {
    let out_file = temp("weights.png");
    let out_path = out_file.to_str().unwrap();
    let weights = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../passes/src/denoise/neural/lucid-rae-v3.safetensors"
    );
    let bad = temp("bad.safetensors");
    std::fs::write(&bad, b"not weights").unwrap();
    let render = |weights: &str| {
        lucid(&[
            "render",
            "--denoise",
            "neural",
            "--neural-weights",
            weights,
            "--size",
            "16x16",
            "--frames",
            "1",
            "--out",
            out_path,
        ])
    };
    let good = render(weights);
    assert!(good.status.success(), "{}", stderr(&good));
    for (file, says) in [
        ("/nonexistent/w.safetensors", "cannot be read"),
        (bad.to_str().unwrap(), "not a valid safetensors file"),
    ] {
        let out = render(file);
        assert!(!out.status.success());
        let err = stderr(&out);
        assert!(err.contains(file) && err.contains(says), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    std::fs::remove_file(&out_file).unwrap();
    std::fs::remove_file(&bad).unwrap();
}

#[test]
fn dataset_writes_records_and_references_with_an_index() {
    let dir = temp("dataset");
    let out = lucid(&[
        "dataset",
        "--out",
        dir.to_str().unwrap(),
        "--size",
        "16x12",
        "--frames",
        "2",
        "--rooms",
        "1",
        "--validation-rooms",
        "1",
        "--sequences",
        "1",
        "--reference-spp",
        "4",
        "--no-builtin",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let index: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("index.json")).unwrap()).unwrap();
    let sequences = index["sequences"].as_array().unwrap();
    let splits: Vec<&str> = sequences
        .iter()
        .map(|s| s["split"].as_str().unwrap())
        .collect();
    assert_eq!(splits, ["train", "validation"]);
    for entry in sequences {
        assert!(entry["scene"].as_str().unwrap().starts_with("random-room-"));
        // Without --stops no camera comes to rest.
        assert!(entry["stop"].is_null(), "{entry}");
        let bytes = std::fs::read(dir.join(entry["file"].as_str().unwrap())).unwrap();
        let tensors = safetensors::SafeTensors::deserialize(&bytes).unwrap();
        let record = tensors.tensor("record").unwrap();
        assert_eq!(record.shape(), [2, 17, 12, 16]);
        assert_eq!(record.dtype(), safetensors::Dtype::F16);
        assert_eq!(tensors.tensor("reference").unwrap().shape(), [2, 3, 12, 16]);
        // Each pixel's object: a room's walls, floor and furniture are objects of their own.
        let objects = tensors.tensor("objects").unwrap();
        assert_eq!(objects.shape(), [2, 12, 16]);
        assert_eq!(objects.dtype(), safetensors::Dtype::I32);
        let ids: Vec<i32> = bytemuck::pod_collect_to_vec(objects.data());
        let distinct: std::collections::BTreeSet<i32> = ids.iter().copied().collect();
        assert!(
            distinct.len() > 1,
            "one object id for the whole room: {distinct:?}"
        );
        assert!(
            ids.iter().all(|&id| (0..1 << 24).contains(&id)),
            "{distinct:?}"
        );
    }
    let odd = lucid(&["dataset", "--out", dir.to_str().unwrap(), "--size", "18x12"]);
    assert!(stderr(&odd).contains("multiples of 4"), "{}", stderr(&odd));

    // Named scenes only, held-out ones included, in the split training never reads.
    let study = temp("dataset-study");
    let out = lucid(&[
        "dataset",
        "--out",
        study.to_str().unwrap(),
        "--size",
        "16x12",
        "--frames",
        "2",
        "--sequences",
        "1",
        "--reference-spp",
        "4",
        "--scenes",
        "caustics,cornell-box",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let index: serde_json::Value =
        serde_json::from_slice(&std::fs::read(study.join("index.json")).unwrap()).unwrap();
    let scenes: Vec<(&str, &str)> = index["sequences"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| (s["scene"].as_str().unwrap(), s["split"].as_str().unwrap()))
        .collect();
    assert_eq!(scenes, [("caustics", "study"), ("cornell-box", "study")]);
    let both = lucid(&[
        "dataset", "--out", "x", "--scenes", "caustics", "--rooms", "2",
    ]);
    assert!(
        stderr(&both).contains("cannot be used with"),
        "{}",
        stderr(&both)
    );
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&study).unwrap();
}

#[test]
fn sequence_evaluates_other_learned_weights_and_second_and_converged_references() {
    let dir = temp("sequence-weights");
    let alternative = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/references/neural_alternative_weights.safetensors"
    );
    let out = lucid(&[
        "sequence",
        "--scene",
        "cornell-box",
        "--size",
        "16x12",
        "--frames",
        "2",
        "--reference-spp",
        "4",
        "--also-neural-weights",
        alternative,
        "--second-reference",
        "--converged-reference-spp",
        "64",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let method = "neural-neural_alternative_weights";
    for frame in ["0000.exr", "0001.exr"] {
        assert!(dir.join(method).join(frame).is_file(), "{method}/{frame}");
    }
    let csv = std::fs::read_to_string(dir.join("metrics.csv")).unwrap();
    let methods: std::collections::BTreeSet<&str> = csv
        .lines()
        .skip(1)
        .filter_map(|line| line.split(',').next())
        .collect();
    for expected in ["none", "spatial", "svgf", "neural", method] {
        assert!(methods.contains(expected), "{expected} in {methods:?}");
        // Each frame's GPU time, and every method on the stability chart.
        let times = std::fs::read_to_string(dir.join(expected).join("gpu_ms.txt")).unwrap();
        let times: Vec<f64> = times.lines().map(|l| l.parse().unwrap()).collect();
        assert!(
            times.len() == 2 && times.iter().all(|&t| t > 0.0),
            "{expected}: {times:?}"
        );
    }
    // A method's mean of one metric (columns: method, frame, rel_mse, ssim, dssim, flip,
    // temporal_instability).
    let mean = |method: &str, column: usize| -> f64 {
        csv.lines()
            .find(|line| line.starts_with(&format!("{method},mean,")))
            .and_then(|line| line.split(',').nth(column)?.parse().ok())
            .unwrap_or_else(|| panic!("{method}'s mean in metrics.csv"))
    };
    // The reference again with another seed: evaluated, and its own noise, so not 0.
    assert!(mean("second-reference", 2) > 0.0);
    // With 16 times the samples, a frame-to-frame change holds the reference's noise about once
    // rather than twice over.
    let second = mean("second-reference", 6);
    let converged = mean("converged-reference", 6);
    assert!(
        converged > 0.0 && converged < 0.7 * second,
        "temporal instability: converged {converged}, second {second}"
    );
    let chart = std::fs::read_to_string(dir.join("stability.svg")).unwrap();
    for expected in ["none", "svgf", "neural", method, "temporal instability"] {
        assert!(
            chart.contains(expected),
            "{expected} on the stability chart"
        );
    }
    assert!(dir.join("stability.png").is_file());
    let bad = lucid(&[
        "sequence",
        "--size",
        "16x12",
        "--also-neural-weights",
        "/nonexistent/w.safetensors",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        stderr(&bad).contains("/nonexistent/w.safetensors"),
        "{}",
        stderr(&bad)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_converged_reference_needs_more_samples_than_the_reference() {
    assert_fails_at_once(
        &[
            "sequence",
            "--size",
            "8x8",
            "--reference-spp",
            "64",
            "--converged-reference-spp",
            "64",
            "--out",
            temp("sequence-converged-spp").to_str().unwrap(),
        ],
        "--converged-reference-spp 64 must exceed --reference-spp 64",
    );
}

/// Fails before any rendering (no device is even opened), with one line naming the problem.
fn assert_fails_at_once(args: &[&str], expect: &str) {
    let started = std::time::Instant::now();
    let out = lucid(args);
    let seconds = started.elapsed().as_secs_f64();
    let err = stderr(&out);
    assert!(!out.status.success(), "{args:?} must fail");
    assert_eq!(err.lines().count(), 1, "{args:?}: one line, got {err:?}");
    assert!(
        err.contains(expect),
        "{args:?}: expected {expect:?} in {err:?}"
    );
    assert!(!err.contains("rendering"), "{args:?} rendered first: {err}");
    assert!(seconds < 5.0, "{args:?} took {seconds:.1} s to fail");
}

#[test]
fn output_paths_are_checked_before_rendering() {
    assert_fails_at_once(
        &[
            "render",
            "--size",
            "8x8",
            "--frames",
            "1",
            "--out",
            "/nonexistent/x.png",
        ],
        "--out /nonexistent/x.png: the folder /nonexistent does not exist",
    );
    assert_fails_at_once(
        &["render", "--size", "8x8", "--out", "x.tiff"],
        "--out x.tiff must end in .png or .exr",
    );
    assert_fails_at_once(
        &[
            "bench",
            "--size",
            "8x8",
            "--frames",
            "1",
            "--json",
            "/nonexistent/b.json",
        ],
        "the folder /nonexistent does not exist",
    );
    assert_fails_at_once(
        &["bench", "--size", "8x8", "--frames", "1", "--json", "b.txt"],
        "--json b.txt must end in .json",
    );
    let plain = temp("plain-file");
    std::fs::write(&plain, b"not a folder").unwrap();
    let under_file = plain.join("out");
    for command in ["sequence", "dataset"] {
        assert_fails_at_once(
            &[
                command,
                "--size",
                "8x8",
                "--out",
                under_file.to_str().unwrap(),
            ],
            "cannot create the folder",
        );
    }
    std::fs::remove_file(&plain).unwrap();
}

#[test]
fn non_finite_float_options_are_refused_with_their_range() {
    for value in ["NaN", "inf", "-inf"] {
        let exposure = format!("--exposure={value}");
        assert_clear_failure(
            &["render", "--size", "8x8", &exposure],
            "'--exposure <EXPOSURE>': must be a finite number from -64 to 64",
        );
        assert_clear_failure(
            &["evaluate", "somewhere", &exposure],
            "must be a finite number from -64 to 64",
        );
        let fps = format!("--fps={value}");
        assert_clear_failure(
            &["sequence", "--size", "8x8", &fps],
            "'--fps <FPS>': must be a finite number from 0.01 to 1000",
        );
    }
}

#[test]
fn dataset_refuses_a_share_of_stops_outside_0_to_1() {
    for value in ["1.5", "-0.1", "NaN", "often"] {
        let stops = format!("--stops={value}");
        assert_clear_failure(
            &["dataset", "--out", "unused", &stops],
            &format!("'--stops <STOPS>': \"{value}\" is not a number from 0 to 1"),
        );
    }
}

#[test]
fn evaluate_without_method_folders_names_the_expected_ones() {
    let dir = temp("evaluate-reference-only");
    let reference = dir.join("reference");
    std::fs::create_dir_all(&reference).unwrap();
    let image = lucid_engine::capture::ImageData::from_pixels(2, 2, vec![[0.5; 4]; 4]).unwrap();
    lucid_engine::capture::save(reference.join("0000.exr"), &image).unwrap();
    assert_fails_at_once(
        &["evaluate", dir.to_str().unwrap()],
        "no method folders to evaluate against reference/ (expected one or more of none/, \
         spatial/, svgf/, neural/, oidn/, second-reference/, converged-reference/)",
    );
    assert!(!dir.join("metrics.csv").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn evaluate_maps_where_each_method_flickers_and_differs() {
    let dir = temp("evaluate-maps");
    // 16x16 frames: a still reference, grey 1 but for a 2x2 block of 3 (2.9x the mean); `none`
    // flickers by 0.5 on that block only, `svgf` is the reference.
    let frame = |block: f32| {
        let pixels = (0..256)
            .map(|i| {
                let v = if (i % 16) < 2 && i / 16 < 2 {
                    block
                } else {
                    1.0
                };
                [v, v, v, 1.0]
            })
            .collect();
        lucid_engine::capture::ImageData::from_pixels(16, 16, pixels).unwrap()
    };
    for (method, blocks) in [
        ("reference", [3.0, 3.0, 3.0]),
        ("svgf", [3.0, 3.0, 3.0]),
        ("none", [3.0, 3.5, 3.0]),
    ] {
        std::fs::create_dir_all(dir.join(method)).unwrap();
        for (i, block) in blocks.into_iter().enumerate() {
            let path = dir.join(method).join(format!("{i:04}.exr"));
            lucid_engine::capture::save(path, &frame(block)).unwrap();
        }
    }
    let out = lucid(&["evaluate", dir.to_str().unwrap(), "--maps"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let printed = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        printed.contains("none: temporal instability 0.0076, 100% of it from pixels over 2x"),
        "{printed}"
    );
    // No pixel is over 8x the mean: each method keeps all of the (absent) light there.
    assert!(
        printed.contains("; 100% of the light over 8x kept"),
        "{printed}"
    );
    for method in ["none", "svgf"] {
        let png = image::open(dir.join("maps").join(format!("{method}.png"))).unwrap();
        assert_eq!((png.width(), png.height()), (16, 16));
        // The block is the scale's top for `none`, everything else its bottom.
        let rgb = png.to_rgb8();
        let (corner, elsewhere) = (rgb.get_pixel(0, 0), rgb.get_pixel(8, 8));
        assert_eq!(corner == elsewhere, method == "svgf", "{method}");
    }
    for method in ["none", "svgf"] {
        let png = image::open(dir.join("maps").join(format!("{method}.flip.png"))).unwrap();
        // `none` differs around the block (FLIP's filters spread it a few pixels), `svgf` nowhere.
        let rgb = png.to_rgb8();
        let (corner, far) = (rgb.get_pixel(0, 0), rgb.get_pixel(15, 15));
        assert_eq!(corner == far, method == "svgf", "{method}");
    }
    let csv = std::fs::read_to_string(dir.join("maps").join("by_brightness.csv")).unwrap();
    assert!(
        csv.starts_with(
            "method,from,to,pixels,instability_share,instability,flip_share,flip,light\n"
        ),
        "{csv}"
    );
    assert!(csv.contains("none,2,8,0.015625,1.000000,"), "{csv}");
    // `none`'s block averages 3.1667 over the frames against the reference's 3.
    assert!(csv.contains(",1.055556\n"), "{csv}");
    assert!(
        csv.contains("svgf,2,8,0.015625,0.000000,0.000000,0.000000,0.000000,1.000000"),
        "{csv}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn evaluate_the_first_frames_as_a_shorter_sequence() {
    // 16x16 frames of one grey each, 3 frames; the reference brightens at frame 2, so the mean
    // brightness that divides the instability differs between the first 2 frames and all 3.
    let write = |dir: &Path, frames: &[(&str, &[f32])]| {
        for (method, greys) in frames {
            std::fs::create_dir_all(dir.join(method)).unwrap();
            for (i, grey) in greys.iter().enumerate() {
                let pixels = vec![[*grey, *grey, *grey, 1.0]; 256];
                let image = lucid_engine::capture::ImageData::from_pixels(16, 16, pixels).unwrap();
                let path = dir.join(method).join(format!("{i:04}.exr"));
                lucid_engine::capture::save(path, &image).unwrap();
            }
        }
    };
    let long = temp("evaluate-first-long");
    write(
        &long,
        &[
            ("reference", &[1.0, 1.0, 4.0]),
            ("none", &[1.0, 1.5, 2.0]),
            ("svgf", &[1.0, 1.2, 3.0]),
        ],
    );
    let short = temp("evaluate-first-short");
    write(
        &short,
        &[
            ("reference", &[1.0, 1.0]),
            ("none", &[1.0, 1.5]),
            ("svgf", &[1.0, 1.2]),
        ],
    );
    let out = lucid(&[
        "evaluate",
        long.to_str().unwrap(),
        "--frames",
        "2",
        "--maps",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        !long.join("metrics.csv").exists(),
        "the whole sequence's untouched"
    );
    let first = long.join("first-2");
    assert!(first.join("maps").join("none.png").exists());
    let out = lucid(&["evaluate", short.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = |dir: &Path| std::fs::read_to_string(dir.join("metrics.csv")).unwrap();
    assert_eq!(csv(&first), csv(&short));
    let out = lucid(&["evaluate", long.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_ne!(
        csv(&long),
        csv(&short),
        "the third frame counts without --frames"
    );
    assert_fails_at_once(
        &["evaluate", long.to_str().unwrap(), "--frames", "4"],
        "reference/ has 3 frames, fewer than the 4 to evaluate",
    );
    assert_clear_failure(
        &["evaluate", long.to_str().unwrap(), "--frames", "1"],
        "'--frames <N>': 1 is not in 2..",
    );
    std::fs::remove_dir_all(&long).unwrap();
    std::fs::remove_dir_all(&short).unwrap();
}

#[test]
fn a_gltf_without_camera_or_light_renders_and_says_what_it_supplied() {
    // One triangle, no camera, no light.
    let file = temp("bare.gltf");
    std::fs::write(
        &file,
        r#"{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36,
               "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]}"#,
    )
    .unwrap();
    let png = temp("bare.png");
    let out = lucid(&[
        "render",
        "--scene",
        file.to_str().unwrap(),
        "--size",
        "16x16",
        "--out",
        png.to_str().unwrap(),
    ]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    let name = file.display().to_string();
    assert!(
        err.contains(&format!(
            "note: no camera in {name}: framing the scene's bounds"
        )),
        "{err}"
    );
    assert!(
        err.contains(&format!(
            "note: no light in {name}: lighting it with a neutral default sky"
        )),
        "{err}"
    );
    assert!(!err.contains("render black"), "{err}");
    let image = image::open(&png).unwrap().to_rgb8();
    assert!(
        image.pixels().all(|p| p.0.iter().any(|&c| c > 20)),
        "every pixel is lit"
    );
    std::fs::remove_file(&file).unwrap();
    std::fs::remove_file(&png).unwrap();
}

/// Writes a `width` x `height` Radiance .hdr of constant radiance `value`.
fn write_hdr(path: &std::path::Path, width: usize, height: usize, value: f32) {
    let texels = vec![image::Rgb([value; 3]); width * height];
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    image::codecs::hdr::HdrEncoder::new(file)
        .encode(&texels, width, height)
        .unwrap();
}

#[test]
fn an_environment_map_lights_the_scene_and_bad_maps_are_named() {
    use lucid_engine::capture::{load_exr, save, ImageData};
    // The furnace's sphere (albedo 0.8) under a constant .hdr map of 0.5 (or the same as .exr):
    // the background shows the map, and the output says what lights the scene.
    let hdr = temp("env-constant.hdr");
    write_hdr(&hdr, 16, 8, 0.5);
    let exr = temp("env-constant.exr");
    let mut map = ImageData::new(16, 8);
    map.pixels.fill([0.5, 0.5, 0.5, 1.0]);
    save(&exr, &map).unwrap();
    for env in [&hdr, &exr] {
        let out_file = temp("env-furnace.exr");
        let out = lucid(&[
            "render",
            "--scene",
            "furnace",
            "--env",
            env.to_str().unwrap(),
            "--size",
            "32x32",
            "--spp",
            "4",
            "--out",
            out_file.to_str().unwrap(),
        ]);
        let err = stderr(&out);
        assert!(out.status.success(), "{err}");
        assert!(
            err.contains("lights the scene") && err.contains("HAS_ENVIRONMENT_MAP"),
            "{err}"
        );
        let image = load_exr(&out_file).unwrap();
        let corner = image.get(0, 0).unwrap();
        assert!(
            (corner[0] - 0.5).abs() < 2e-3,
            "{env:?}: background {corner:?}"
        );
    }
    let wide = temp("env-square.hdr");
    write_hdr(&wide, 8, 8, 1.0);
    for (file, says) in [
        (temp("env-missing.hdr"), "env-missing.hdr"),
        (temp("env.png"), ".hdr or .exr"),
        (wide.clone(), "twice as wide as high"),
    ] {
        let out = lucid(&["render", "--env", file.to_str().unwrap(), "--size", "8x8"]);
        let err = stderr(&out);
        assert!(!out.status.success(), "{file:?} must fail");
        assert!(err.contains(says) && !err.contains("panicked"), "{err}");
    }
    for file in [hdr, exr, temp("env-furnace.exr"), wide] {
        std::fs::remove_file(file).unwrap();
    }
}
