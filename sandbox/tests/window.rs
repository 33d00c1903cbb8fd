//! `lucid view` in a real window under Xvfb (lavapipe when there is no GPU, validation on): the
//! split view's screenshot shows both configurations, a divider and a label per half; the window
//! self-test shrinks the window, minimizes it, restores it and loses its surface, and the app keeps
//! running and ends cleanly.

mod support;

use lucid_engine::capture::{load_png, ImageData};
use std::ops::Range;
use std::process::Command;
use support::xvfb::{check_clean_exit, Xvfb};

const WIDTH: u32 = 960;
const HEIGHT: u32 = 400;

fn temp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("lucid-window-{}-{name}", std::process::id()))
}

/// Runs `lucid view ARGS --size WIDTHxHEIGHT --screenshot-after FRAMES <file>`; returns the
/// screenshot and what the app printed on stderr.
fn screenshot(args: &[&str], frames: u32, name: &str) -> Result<(ImageData, String), String> {
    let shot = temp(name);
    let mut command = Command::new(env!("CARGO_BIN_EXE_lucid"));
    command
        .arg("view")
        .args(args)
        .args(["--size", &format!("{WIDTH}x{HEIGHT}")])
        .arg("--screenshot-after")
        .arg(frames.to_string())
        .arg(&shot);
    let xvfb = Xvfb::start()?;
    let stderr = check_clean_exit(&xvfb.run(command)?)?;
    let image = load_png(&shot).map_err(|e| format!("reading the screenshot: {e}"))?;
    std::fs::remove_file(&shot).map_err(|e| e.to_string())?;
    if (image.width, image.height) != (WIDTH, HEIGHT) {
        return Err(format!(
            "the screenshot is {}x{}",
            image.width, image.height
        ));
    }
    Ok((image, stderr))
}

fn luminance(p: [f32; 4]) -> f32 {
    0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]
}

/// Mean difference between horizontal neighbours relative to the mean: how noisy a flat region is.
fn roughness(image: &ImageData, xs: Range<u32>, ys: Range<u32>) -> f32 {
    let at = |x: u32, y: u32| luminance(image.pixels[(y * image.width + x) as usize]);
    let (mut steps, mut sum) = (0.0, 0.0);
    for y in ys {
        for x in xs.start..xs.end - 1 {
            steps += (at(x + 1, y) - at(x, y)).abs();
            sum += at(x, y);
        }
    }
    steps / sum.max(1e-6)
}

/// Pixels in columns `xs` and rows `ys` that pass `test`.
fn count(
    image: &ImageData,
    xs: Range<u32>,
    ys: Range<u32>,
    test: impl Fn([f32; 4]) -> bool,
) -> usize {
    ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
        .filter(|&(x, y)| test(image.pixels[(y * image.width + x) as usize]))
        .count()
}

#[test]
fn split_view_shows_two_configurations_a_divider_and_labels() {
    // Left: path tracing with SVGF; right: the same without a denoiser.
    let (image, _) = screenshot(
        &["cornell-box", "--denoise", "svgf", "--split", "pt/none"],
        6,
        "split.png",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let split = WIDTH / 2;

    // The divider: a yellow line (sRGB 255, 200, 0) down the middle, on every row.
    let divider = |p: [f32; 4]| p[0] > 0.9 && p[1] > 0.45 && p[1] < 0.7 && p[2] < 0.05;
    let rows_with_divider = (0..HEIGHT)
        .filter(|&y| count(&image, split - 2..split + 2, y..y + 1, divider) > 0)
        .count();
    assert_eq!(
        rows_with_divider, HEIGHT as usize,
        "the divider runs down the middle"
    );
    let elsewhere = count(&image, 0..split - 40, 0..HEIGHT, divider);
    assert!(
        elsewhere < 50,
        "{elsewhere} divider-coloured pixels away from it"
    );

    // A label on each side of it: white text on dark boxes at the top.
    let text = |p: [f32; 4]| p[0] > 0.85 && p[1] > 0.85 && p[2] > 0.85;
    let left_text = count(&image, split - 200..split - 10, 8..40, text);
    let right_text = count(&image, split + 10..split + 100, 8..40, text);

    // The back wall beside the divider: smooth where SVGF denoised it, noisy where it did not.
    let rows = 75..160;
    let left = roughness(&image, split - 70..split - 10, rows.clone());
    let right = roughness(&image, split + 10..split + 70, rows);
    println!(
        "divider rows {rows_with_divider}/{HEIGHT}; label text pixels {left_text} | {right_text}; \
         back wall roughness {left:.4} (SVGF) | {right:.4} (none)"
    );
    assert!(
        left_text > 40 && right_text > 40,
        "labels: {left_text} | {right_text} text pixels"
    );
    assert!(
        right > 4.0 * left,
        "the undenoised half is noisier: {left:.4} (SVGF) vs {right:.4} (none)"
    );
}

/// The frame number of the window test's line containing `step`.
fn step_frame(stderr: &str, step: &str) -> Result<u64, String> {
    let line = stderr
        .lines()
        .find(|l| l.starts_with("window test: ") && l.contains(step))
        .ok_or_else(|| format!("no window test step {step:?} in:\n{stderr}"))?;
    line.trim_start_matches("window test: frame ")
        .split(':')
        .next()
        .and_then(|n| n.parse().ok())
        .ok_or_else(|| format!("no frame number in {line:?}"))
}

#[test]
fn the_window_survives_shrinking_minimizing_and_losing_its_surface() {
    let (image, stderr) = screenshot(&["cornell-box", "--window-test"], 14, "window-test.png")
        .unwrap_or_else(|e| panic!("{e}"));
    let frame = |step| step_frame(&stderr, step).unwrap_or_else(|e| panic!("{e}"));
    let shrunk = frame("asked for 96x64");
    let minimized = frame("minimized at 96x64");
    let restored = frame("restored after");
    let lost = frame("surface lost");
    println!("steps at frames: shrunk {shrunk}, minimized {minimized}, restored {restored}, surface lost {lost}");
    assert!(shrunk < minimized, "frames at the tiny size came between");
    assert_eq!(
        minimized, restored,
        "no frame was presented while minimized"
    );
    assert!(
        restored < lost && lost < 14,
        "the surface was lost before the screenshot"
    );
    assert!(
        stderr.contains("the window surface was lost; creating a new one"),
        "the surface was made anew:\n{stderr}"
    );
    // The screenshot (after the new surface) has the restored size and shows the scene.
    let red = count(&image, 0..WIDTH / 2, 0..HEIGHT, |p| {
        p[0] > 0.3 && p[0] > 2.0 * p[1] + 2.0 * p[2]
    });
    println!("red wall pixels after the steps: {red}");
    assert!(
        red > 2000,
        "the Cornell box's red wall shows ({red} pixels)"
    );
}
