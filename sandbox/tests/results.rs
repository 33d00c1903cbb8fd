//! `docs/results/generate.sh`, the script that measures and writes the published results, run
//! small on the machine's device (lavapipe in CI) so that it cannot rot: its tables and charts.

use std::process::Command;

#[test]
fn the_results_script_writes_its_tables_and_charts() {
    let out = std::env::temp_dir().join(format!("lucid-test-{}-results", std::process::id()));
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/results/generate.sh");
    let run = Command::new("bash")
        .arg(script)
        .arg(&out)
        .envs([
            ("LUCID", env!("CARGO_BIN_EXE_lucid")),
            ("LUCID_VALIDATION", "1"),
            ("SCENES", "cornell-box"),
            ("SIZE", "24x24"),
            ("TABLE_SIZES", "24x24 32x24"),
            ("DENOISER_SIZES", "24x24"),
            ("ALGOS", "pt"),
            ("DENOISERS", "none,svgf"),
            ("SPP", "1"),
            ("BUDGET_MS", "30"),
            ("REFERENCE_SPP", "16"),
            ("FRAMES", "2"),
            ("STABILITY_SIZE", "16x12"),
            ("STABILITY_FRAMES", "2"),
            ("STABILITY_REFERENCE_SPP", "4"),
        ])
        .output()
        .expect("run bash");
    let log = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{log}");
    let page = std::fs::read_to_string(out.join("README.md")).expect("README.md");
    for heading in [
        "Table 4.1",
        "Table 4.2",
        "Table 4.3",
        "## cornell-box",
        "| cornell-box | 24x24 |",
        "| cornell-box | 32x24 |",
        "| svgf |",
        "| pt/none/1",
        "| pt/svgf/1",
        "Stability against time per frame",
        "| svgf | ",
        "stability/stability.svg",
        "cornell-box/time_to_converge.svg",
        "the first frame to reach each of the same GPU times (0.03, ",
    ] {
        assert!(page.contains(heading), "{heading} missing from:\n{page}");
    }
    for chart in [
        "speed_vs_accuracy.svg",
        "error_vs_time_dssim.svg",
        "time_to_converge.svg",
    ] {
        assert!(out.join("cornell-box").join(chart).exists(), "{chart}");
    }
    let commands = std::fs::read_to_string(out.join("commands.txt")).expect("commands.txt");
    assert!(out.join("stability").join("stability.svg").exists());
    assert_eq!(commands.lines().count(), 1 + 2 * 2 + 2 + 1, "{commands}");
    std::fs::remove_dir_all(&out).ok();
}
