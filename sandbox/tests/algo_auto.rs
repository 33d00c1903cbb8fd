//! `--algo auto` on the command line (lavapipe, tiny): the calibration's table and choice are
//! printed, the render uses the choice, and a goal without `--algo auto` is refused.

mod run_lucid;
use run_lucid::{lucid, stderr, temp};

#[test]
fn render_with_algo_auto_prints_the_measurements_and_renders_the_choice() {
    let out_file = temp("auto.png");
    let out = lucid(&[
        "render",
        "--scene",
        "cornell-box",
        "--size",
        "24x24",
        "--frames",
        "1",
        "--algo",
        "auto",
        // Fixed denoiser and samples: the calibration chooses between the two algorithms only.
        "--denoise",
        "svgf",
        "--spp",
        "1",
        "--calibration-frames",
        "2",
        "--calibration-reference-spp",
        "32",
        "--budget-ms",
        "1000000",
        "--out",
        out_file.to_str().unwrap(),
    ]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains("VUID"), "validation messages: {err}");
    for config in ["pt/svgf/1", "bdpt/svgf/1"] {
        assert!(
            err.lines().any(|l| l.starts_with(config)),
            "{config} measured: {err}"
        );
    }
    let choice = err
        .lines()
        .filter_map(|l| l.strip_prefix("auto: "))
        .find(|l| l.contains(" for at most 1000000 ms per frame, least DSSIM"))
        .unwrap_or_else(|| panic!("the choice is printed: {err}"));
    let chosen = choice.split(' ').next().unwrap();
    assert!(["pt/svgf/1", "bdpt/svgf/1"].contains(&chosen), "{choice}");
    let algorithm = if chosen.starts_with("bdpt") {
        "bidirectional"
    } else {
        "path tracing"
    };
    assert!(
        err.contains(&format!("1 spp, {algorithm}, denoiser SVGF")),
        "the render uses the choice: {err}"
    );
    assert!(std::fs::metadata(&out_file).is_ok());
    std::fs::remove_file(&out_file).unwrap();
}

#[test]
fn a_goal_without_algo_auto_is_refused() {
    for goal in ["--quality=0.1", "--budget-ms=8"] {
        let out = lucid(&["render", "--size", "8x8", "--algo", "pt", goal]);
        let err = stderr(&out);
        assert!(!out.status.success(), "{goal}");
        assert!(err.contains("add --algo auto"), "{goal}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    let out = lucid(&[
        "render",
        "--algo",
        "auto",
        "--quality",
        "0.1",
        "--budget-ms",
        "8",
    ]);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("cannot be used with"),
        "{}",
        stderr(&out)
    );
}
