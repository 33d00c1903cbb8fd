//! `lucid converge` on the machine's device (lavapipe in CI), tiny: its files, its numbers, and
//! clear errors for bad input.

use std::collections::BTreeMap;
use std::path::Path;

mod run_lucid;
use run_lucid::{lucid, stderr, temp};

const METRICS: [&str; 3] = ["dssim", "flip", "rel_mse"];

/// The GPU time each configuration of the measuring test spends: several frames of 32x32 on
/// lavapipe.
const BUDGET_MS: &str = "300";

/// The most frames each configuration of the measuring test renders.
const MAX_FRAMES: &str = "1000";

/// Equal but for serde_json's parsing, which may be one unit in the last place off.
fn same(json: Option<f64>, csv: Option<f64>) -> bool {
    match (json, csv) {
        (Some(a), Some(b)) => (a - b).abs() <= 1e-12 * b.abs().max(1e-300),
        (a, b) => a == b,
    }
}

/// One CSV row.
#[derive(Debug)]
struct Row {
    frame: u32,
    target_ms: Option<f64>,
    gpu_ms: f64,
    frame_ms: f64,
    errors: BTreeMap<&'static str, f64>,
}

/// The CSV's rows per configuration, checking its header and per-row consistency.
fn read_csv(path: &Path) -> BTreeMap<String, Vec<Row>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("config,algo,denoiser,spp,frame,target_ms,gpu_ms,frame_ms,dssim,flip,rel_mse")
    );
    let mut configs: BTreeMap<String, Vec<Row>> = BTreeMap::new();
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 11, "{line}");
        assert_eq!(f[0], format!("{}/{}/{}", f[1], f[2], f[3]), "{line}");
        let number = |i: usize| f[i].parse::<f64>().unwrap();
        let errors = METRICS
            .iter()
            .enumerate()
            .map(|(k, &m)| (m, number(8 + k)))
            .collect();
        configs.entry(f[0].to_string()).or_default().push(Row {
            frame: f[4].parse().unwrap(),
            target_ms: (!f[5].is_empty()).then(|| number(5)),
            gpu_ms: number(6),
            frame_ms: number(7),
            errors,
        });
    }
    configs
}

/// Checks that `rows` were measured at every time of `ladder` the configuration reached, each at
/// or past it, nearly all at the first frame to reach it (their time at most one frame past the
/// target: only a frame taking more than `tradeoff::measure::REACH` times the one before it,
/// which a loaded lavapipe can show now and then, leaves a target to the next frame), and at the
/// last frame. A configuration that spent the budget within `MAX_FRAMES` reached the whole
/// ladder, the budget last (lavapipe's do); one that rendered `MAX_FRAMES` first (a fast GPU's:
/// an H200 renders them in about 110 ms) reached the times up to its last frame's, and that frame
/// is one more row, without a target.
fn assert_measured_at_the_ladder(config: &str, rows: &[Row], ladder: &[f64]) {
    let last = rows.last().expect("rows");
    let capped = last.target_ms.is_none();
    let reached: Vec<f64> = if capped {
        assert_eq!(last.frame.to_string(), MAX_FRAMES, "{config}: {last:?}");
        assert!(
            last.gpu_ms < ladder[ladder.len() - 1],
            "{config}: the budget was spent, yet no row at it: {last:?}"
        );
        ladder
            .iter()
            .copied()
            .filter(|&t| t <= last.gpu_ms)
            .collect()
    } else {
        ladder.to_vec()
    };
    let targets: Vec<f64> = rows.iter().filter_map(|r| r.target_ms).collect();
    assert_eq!(
        targets, reached,
        "{config}: the same target times: {rows:?}"
    );
    let measured = &rows[..rows.len() - usize::from(capped)];
    let mut late = 0;
    for row in measured {
        let target = row.target_ms.unwrap();
        assert!(row.gpu_ms >= target, "{config}: before its target: {row:?}");
        if row.gpu_ms - row.frame_ms >= target * (1.0 + 1e-12) {
            late += 1;
        }
        assert!(row.frame_ms > 0.0, "{config}: {row:?}");
    }
    assert!(
        late * 5 <= measured.len(),
        "{config}: {late} of {} rows more than one frame past their target: {rows:?}",
        measured.len()
    );
    for w in rows.windows(2) {
        if w[0].frame == w[1].frame {
            assert_eq!(w[0].gpu_ms, w[1].gpu_ms, "{config}: one frame, one time");
            assert_eq!(w[0].errors, w[1].errors, "{config}: one frame, one image");
        } else {
            assert!(w[1].frame > w[0].frame, "{config}: frames in order");
            assert!(
                w[1].gpu_ms - w[1].frame_ms >= w[0].gpu_ms * (1.0 - 1e-12),
                "{config}: GPU time accumulates: {w:?}"
            );
        }
    }
}

#[test]
fn converge_writes_errors_that_fall_as_samples_accumulate_and_charts() {
    let dir = temp("run");
    let out = lucid(&[
        "converge",
        "--scene",
        "cornell-box",
        "--size",
        "32x32",
        "--algos",
        "pt",
        "--denoisers",
        "none,svgf",
        "--spp",
        "1,2",
        "--max-frames",
        MAX_FRAMES,
        "--budget-ms",
        BUDGET_MS,
        // relMSE divides by the reference: a 16-sample one has dark pixels where it is lit.
        "--reference-spp",
        "64",
        "--target-flip",
        "1",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains("VUID"), "validation messages: {err}");
    let printed: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("converge.json")).unwrap()).unwrap();
    assert_eq!(printed, json, "--json prints what converge.json holds");
    assert_eq!(json["scene"], "cornell-box");
    assert_eq!(json["size"], serde_json::json!([32, 32]));
    assert!(json["device"].as_str().is_some_and(|d| !d.is_empty()));
    assert!(json["command"].as_str().unwrap().contains("converge"));

    let csv = read_csv(&dir.join("converge.csv"));
    let names: Vec<&str> = csv.keys().map(String::as_str).collect();
    assert_eq!(names, ["pt/none/1", "pt/none/2", "pt/svgf/1", "pt/svgf/2"]);
    // Each configuration is measured at the ladder's times it reached: on lavapipe all of them,
    // the budget last.
    let ladder: Vec<f64> = json["time_ladder_ms"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect();
    let budget: f64 = BUDGET_MS.parse().unwrap();
    assert_eq!(ladder.len(), 3 * 6 + 1, "{ladder:?}");
    assert_eq!(
        (ladder[0], ladder[ladder.len() - 1]),
        (budget / 1000.0, budget)
    );
    for (config, rows) in &csv {
        assert_measured_at_the_ladder(config, rows, &ladder);
        assert!(rows[0].gpu_ms > 0.0, "{config}");
        assert!(
            rows.last().unwrap().frame > 1,
            "{config}: more than one frame in the budget: {rows:?}"
        );
        for row in rows {
            for (metric, value) in &row.errors {
                assert!(
                    value.is_finite() && *value >= 0.0,
                    "{config} {metric}: {row:?}"
                );
            }
        }
    }
    // Without a denoiser, accumulating samples brings every error down.
    for config in ["pt/none/1", "pt/none/2"] {
        let rows = &csv[config];
        let (first, last) = (&rows[0], &rows[rows.len() - 1]);
        for metric in METRICS {
            assert!(
                last.errors[metric] < first.errors[metric],
                "{config}: {metric} must fall from {} (1 frame) to {} ({} frames)",
                first.errors[metric],
                last.errors[metric],
                last.frame
            );
        }
    }

    // The JSON's times to converge are those of the CSV's rows.
    let targets = &json["targets"];
    assert_eq!(targets["flip"], 1.0);
    assert_eq!(targets["dssim"], 0.1);
    assert_eq!(targets["rel_mse"], 0.01);
    let configurations = json["configurations"].as_array().unwrap();
    assert_eq!(configurations.len(), 4);
    for c in configurations {
        let name = c["config"].as_str().unwrap();
        let rows = &csv[name];
        let last = &rows[rows.len() - 1];
        assert_eq!(c["frames"], last.frame);
        let json_rows = c["rows"].as_array().unwrap();
        assert_eq!(json_rows.len(), rows.len());
        for (j, row) in json_rows.iter().zip(rows) {
            assert!(same(j["target_ms"].as_f64(), row.target_ms), "{name}: {j}");
            assert!(same(j["gpu_ms"].as_f64(), Some(row.gpu_ms)), "{name}: {j}");
            assert!(
                same(j["frame_ms"].as_f64(), Some(row.frame_ms)),
                "{name}: {j}"
            );
        }
        for metric in METRICS {
            let target = targets[metric].as_f64().unwrap();
            let expected = rows
                .iter()
                .find(|r| r.errors[metric] < target)
                .map(|r| r.gpu_ms);
            let time = c["time_to_converge_ms"][metric].as_f64();
            assert!(
                same(time, expected),
                "{name} {metric}: {time:?} {expected:?}"
            );
            let last = Some(rows[rows.len() - 1].errors[metric]);
            let end = c["final"][metric].as_f64();
            assert!(same(end, last), "{name} {metric}: {end:?} {last:?}");
        }
        // FLIP is below 1 from the first frame on.
        let flip = c["time_to_converge_ms"]["flip"].as_f64();
        assert!(same(flip, Some(rows[0].gpu_ms)), "{name}: {flip:?}");
        let per_frame = c["gpu_ms_per_frame"].as_f64().unwrap();
        let frames = f64::from(last.frame);
        assert!((per_frame * frames - last.gpu_ms).abs() < 1e-9 * last.gpu_ms.max(1.0));
    }
    for metric in METRICS {
        let front = json["pareto_front"][metric].as_array().unwrap();
        assert!(!front.is_empty(), "{metric}: a front of at least one point");
    }

    let mut charts: Vec<String> = METRICS
        .iter()
        .map(|m| format!("error_vs_time_{m}"))
        .collect();
    charts.extend(["speed_vs_accuracy".into(), "time_to_converge".into()]);
    for chart in charts {
        let png = std::fs::read(dir.join(format!("{chart}.png"))).unwrap();
        assert!(png.starts_with(b"\x89PNG"), "{chart}.png");
        let image = image::load_from_memory(&png).unwrap();
        assert!(image.width() >= 400 && image.height() >= 300, "{chart}.png");
        let svg = std::fs::read_to_string(dir.join(format!("{chart}.svg"))).unwrap();
        assert!(
            svg.contains("<svg") && svg.contains("pt/svgf/2"),
            "{chart}.svg"
        );
    }
    // A configuration that never reached a target is marked on the time-to-converge chart.
    let never = configurations.iter().any(|c| {
        METRICS
            .iter()
            .any(|m| c["time_to_converge_ms"][m].is_null())
    });
    let svg = std::fs::read_to_string(dir.join("time_to_converge.svg")).unwrap();
    assert_eq!(svg.contains("never in"), never, "never-converged marks");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Fails at once with one line naming the problem, without panicking.
fn assert_clear_failure(args: &[&str], expect: &str) {
    let mut full = vec!["converge", "--size", "8x8"];
    full.extend_from_slice(args);
    let started = std::time::Instant::now();
    let out = lucid(&full);
    let err = stderr(&out);
    assert!(!out.status.success(), "{full:?} must fail");
    assert!(
        err.contains(expect),
        "{full:?}: expected {expect:?} in {err:?}"
    );
    assert!(!err.contains("panicked"), "{full:?} panicked: {err}");
    assert!(
        !err.contains("reference:"),
        "{full:?} rendered first: {err}"
    );
    assert!(
        started.elapsed().as_secs_f64() < 5.0,
        "{full:?} was slow to fail"
    );
}

#[test]
fn converge_refuses_bad_lists_and_targets_clearly() {
    assert_clear_failure(
        &["--algos", "pt,mlt"],
        "unknown algorithm \"mlt\" (expected pt, bdpt, pt-wavefront, pt-wavefront-binned)",
    );
    assert_clear_failure(
        &["--denoisers", "oidn"],
        "unknown denoiser \"oidn\" (expected none, svgf, neural)",
    );
    assert_clear_failure(&["--algos", ""], "the list is empty");
    assert_clear_failure(&["--denoisers", "none,"], "an empty denoiser");
    assert_clear_failure(&["--spp", "1,0"], "\"0\" is not a sample count");
    assert_clear_failure(&["--spp", "2,2"], "listed twice");
    for value in ["NaN", "inf", "-inf", "-0.1"] {
        for option in ["--target-dssim", "--target-flip", "--target-relmse"] {
            assert_clear_failure(&[&format!("{option}={value}")], "must be a finite number");
        }
        assert_clear_failure(
            &[&format!("--budget-ms={value}")],
            "must be a finite number",
        );
    }
    assert_clear_failure(&["--max-frames", "0"], "--max-frames");
    let plain = temp("plain-file");
    std::fs::write(&plain, b"not a folder").unwrap();
    let under_file = plain.join("out");
    assert_clear_failure(
        &["--out", under_file.to_str().unwrap()],
        "cannot create the folder",
    );
    std::fs::remove_file(&plain).unwrap();
}

/// Renders `cornell-box` at 24x24 into `path` (an EXR of the HDR image).
fn render_exr(path: &Path, spp: &str, seed: &str) {
    let out = lucid(&[
        "render",
        "--scene",
        "cornell-box",
        "--size",
        "24x24",
        "--spp",
        spp,
        "--seed",
        seed,
        "--frames",
        "1",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "render: {}", stderr(&out));
}

#[test]
fn converge_measures_another_renderers_series_against_a_reference_file() {
    let dir = temp("external");
    std::fs::create_dir_all(&dir).unwrap();
    // Another "renderer": lucid render's own images, so its errors must match converge's own
    // configuration at the same sample count.
    render_exr(&dir.join("reference.exr"), "1024", "99");
    render_exr(&dir.join("other_4.exr"), "4", "7");
    render_exr(&dir.join("other_64.exr"), "64", "8");
    let series = serde_json::json!({
        "renderer": "lucid render",
        "time": "wall",
        "points": [
            {"spp": 64, "ms": 16.0, "image": "other_64.exr"},
            {"spp": 4, "ms": 1.5, "image": "other_4.exr"},
        ],
    });
    let series_file = dir.join("series.json");
    std::fs::write(&series_file, series.to_string()).unwrap();
    let out_dir = dir.join("out");
    let out = lucid(&[
        "converge",
        "--size",
        "24x24",
        "--algos",
        "pt",
        "--denoisers",
        "none",
        "--spp",
        "4",
        "--max-frames",
        "1",
        "--reference",
        dir.join("reference.exr").to_str().unwrap(),
        "--external",
        &format!("Other, renderer={}", series_file.display()),
        "--out",
        out_dir.to_str().unwrap(),
        "--json",
    ]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains("reference:"), "rendered a reference: {err}");
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(json["reference"]
        .as_str()
        .unwrap()
        .contains("reference.exr"));
    assert!(json["reference_spp"].is_null());
    let external = &json["external"][0];
    assert_eq!(external["name"], "Other, renderer");
    assert_eq!(external["renderer"], "lucid render");
    let points = external["points"].as_array().unwrap();
    let spp: Vec<u64> = points.iter().map(|p| p["spp"].as_u64().unwrap()).collect();
    assert_eq!(spp, [4, 64], "sorted by samples per pixel");
    assert_eq!(points[0]["ms"], 1.5);
    for metric in METRICS {
        let few = points[0][metric].as_f64().unwrap();
        let many = points[1][metric].as_f64().unwrap();
        assert!(many < few, "{metric}: 64 spp {many} not below 4 spp {few}");
    }
    // Measured as converge measures its own: 4 samples of the same renderer, the same error.
    let own = json["configurations"][0]["final"]["rel_mse"]
        .as_f64()
        .unwrap();
    let other = points[0]["rel_mse"].as_f64().unwrap();
    assert!(
        (0.5..2.0).contains(&(other / own)),
        "relMSE at 4 spp: external {other}, pt/none/4 {own}"
    );
    let csv = std::fs::read_to_string(out_dir.join("converge.csv")).unwrap();
    assert!(
        csv.lines()
            .any(|l| l.starts_with("\"Other, renderer\",,,64,1,,16,16,")),
        "{csv}"
    );
    let svg = std::fs::read_to_string(out_dir.join("error_vs_time_rel_mse.svg")).unwrap();
    assert!(svg.contains("Other, renderer (wall time)"), "legend");

    // Bad input: one clear line each, before any rendering.
    let reference = dir.join("reference.exr");
    assert_clear_failure(
        &["--reference", reference.to_str().unwrap()],
        "is 24x24, --size 8x8",
    );
    assert_clear_failure(&["--external", "series.json"], "expected NAME=FILE");
    let missing = dir.join("missing.json");
    assert_clear_failure(
        &["--external", &format!("X={}", missing.display())],
        "reading --external",
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
