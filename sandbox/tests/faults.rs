//! Faults on the device end `lucid` with one clear line and a non-zero exit, no panic and no
//! output file: a lost device (injected with `LUCID_INJECT_DEVICE_LOST`), a frame or a scene that
//! does not fit in device memory (the device's heap, or `LUCID_MEMORY_BUDGET_MIB`).

mod run_lucid;
use run_lucid::{lucid, lucid_with_env, stderr, temp};

/// The run failed with one `error:` line containing `expect`, no panic, and left no `out` file.
fn assert_one_line_failure(out: &std::process::Output, expect: &str, file: &std::path::Path) {
    let err = stderr(out);
    assert!(!out.status.success(), "must fail: {err}");
    assert!(!err.contains("panicked"), "{err}");
    let errors: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "one error line: {err}");
    assert!(errors[0].contains(expect), "expected {expect:?} in {err}");
    assert!(!file.exists(), "{} must not be written", file.display());
}

#[test]
fn a_lost_device_ends_a_render_with_a_clear_error_and_no_file() {
    let out_file = temp("device-lost.png");
    let path = out_file.to_str().unwrap();
    let args = ["render", "--size", "16x16", "--frames", "4", "--out", path];
    let out = lucid_with_env(&args, &[("LUCID_INJECT_DEVICE_LOST", "2")]);
    assert_one_line_failure(&out, "the GPU device was lost", &out_file);
    let err = stderr(&out);
    assert!(
        err.contains("submission of frame 2 (passes "),
        "names the frame and its passes: {err}"
    );
    let out = lucid(&args);
    assert!(out.status.success(), "without the fault: {}", stderr(&out));
    std::fs::remove_file(&out_file).unwrap();
}

#[test]
fn a_16k_frame_beyond_device_memory_is_refused_before_it_runs() {
    // 2 GiB: lavapipe's heap; on a GPU with more memory the budget stands in for it.
    let out_file = temp("16k.png");
    let started = std::time::Instant::now();
    let out = lucid_with_env(
        &[
            "render",
            "--size",
            "16384x16384",
            "--frames",
            "1",
            "--out",
            out_file.to_str().unwrap(),
        ],
        &[("LUCID_MEMORY_BUDGET_MIB", "2048")],
    );
    assert_one_line_failure(&out, "out of device memory: ", &out_file);
    let err = stderr(&out);
    assert!(
        err.contains("MiB for the frame's") && err.contains("lower the resolution"),
        "says what does not fit and what to do: {err}"
    );
    let seconds = started.elapsed().as_secs_f64();
    assert!(
        seconds < 30.0,
        "refused before rendering, took {seconds:.1} s"
    );
}

#[test]
fn a_scene_beyond_the_memory_budget_is_refused() {
    let out_file = temp("budget.png");
    let out = lucid_with_env(
        &[
            "render",
            "--scene",
            "cornell-teapot",
            "--size",
            "16x16",
            "--frames",
            "1",
            "--out",
            out_file.to_str().unwrap(),
        ],
        &[("LUCID_MEMORY_BUDGET_MIB", "2")],
    );
    assert_one_line_failure(
        &out,
        "left of the budget LUCID_MEMORY_BUDGET_MIB=2",
        &out_file,
    );
}
