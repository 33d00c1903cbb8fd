//! The interactive sandbox in a real window: under Xvfb (on lavapipe when there is no GPU, with
//! validation on) it starts, renders frames, saves a screenshot of the window by itself and exits
//! cleanly; the screenshot must show the scene and the UI panel.
//!
//! winit needs the main thread, so this test has its own `main` (`harness = false`): it starts
//! Xvfb, then runs itself again as the app process (`LUCID_SANDBOX_TEST_SHOT` set), and checks
//! that process's exit status, output and screenshot.

#[allow(dead_code)]
#[path = "../../sandbox/tests/support/xvfb.rs"]
mod xvfb;

use lucid_engine::capture::{load_png, ImageData};
use lucid_sandbox::{AppOptions, Screenshot};
use std::path::PathBuf;
use std::process::{Command, ExitCode};
use xvfb::{check_clean_exit, Xvfb};

/// Set in the app process: where to write the screenshot.
const CHILD_VAR: &str = "LUCID_SANDBOX_TEST_SHOT";
const WIDTH: u32 = 800;
const HEIGHT: u32 = 600;
/// Frames before the screenshot.
const FRAMES: u64 = 5;

fn main() -> ExitCode {
    if let Some(shot) = std::env::var_os(CHILD_VAR) {
        return app(PathBuf::from(shot));
    }
    match check_sandbox() {
        Ok(()) => {
            println!("test sandbox_xvfb ... ok\n\ntest result: ok. 1 passed; 0 failed; 0 ignored");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("sandbox_xvfb failed: {e}");
            println!("test sandbox_xvfb ... FAILED\n\ntest result: FAILED. 0 passed; 1 failed; 0 ignored");
            ExitCode::FAILURE
        }
    }
}

/// The app process: the sandbox as `lucid view --screenshot-after 5 <shot>` runs it.
fn app(shot: PathBuf) -> ExitCode {
    let options = AppOptions {
        scene: "cornell-box".into(),
        env: None,
        size: [WIDTH, HEIGHT],
        capture_dir: std::env::temp_dir(),
        screenshot: Some(Screenshot {
            after_frames: FRAMES,
            path: shot,
        }),
    };
    match lucid_sandbox::run(options) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn check_sandbox() -> Result<(), String> {
    let shot = std::env::temp_dir().join(format!("lucid-sandbox-{}.png", std::process::id()));
    let xvfb = Xvfb::start()?;
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut app = Command::new(exe);
    app.env(CHILD_VAR, &shot);
    let output = xvfb.run(app);
    drop(xvfb);
    check_clean_exit(&output?)?;
    let image = load_png(&shot).map_err(|e| format!("reading the screenshot: {e}"))?;
    std::fs::remove_file(&shot).map_err(|e| e.to_string())?;
    check_screenshot(&image)
}

/// The screenshot has the window's size, the scene on the left and the egui panel on the right (a
/// flat dark grey with text).
fn check_screenshot(image: &ImageData) -> Result<(), String> {
    if (image.width, image.height) != (WIDTH, HEIGHT) {
        return Err(format!(
            "screenshot is {}x{}, the window {WIDTH}x{HEIGHT}",
            image.width, image.height
        ));
    }
    // The default scene is the Cornell box: its red wall fills part of the left half, and its lit
    // interior varies in brightness.
    let scene = region(image, 20..WIDTH / 2, 20..HEIGHT - 60);
    let red = scene
        .iter()
        .filter(|p| p[0] > 0.3 && p[0] > 2.0 * p[1] && p[0] > 2.0 * p[2])
        .count();
    if red * 20 < scene.len() {
        return Err(format!(
            "the scene region does not show the Cornell box's red wall ({red} of {} pixels red)",
            scene.len()
        ));
    }
    let luminance_std = std_dev(
        scene
            .iter()
            .map(|p| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]),
    );
    if luminance_std < 0.05 {
        return Err(format!(
            "the scene region is flat (luminance std {luminance_std:.3})"
        ));
    }
    let panel = region(image, WIDTH - 200..WIDTH - 10, 40..HEIGHT - 60);
    let dark_grey = panel
        .iter()
        .filter(|p| p[0] < 0.1 && (p[0] - p[1]).abs() < 0.01 && (p[1] - p[2]).abs() < 0.01)
        .count();
    if dark_grey * 2 < panel.len() {
        return Err(format!(
            "the right side is not the UI panel ({dark_grey} of {} pixels dark grey)",
            panel.len()
        ));
    }
    let text = panel.iter().filter(|p| p[0] + p[1] + p[2] > 0.3).count();
    if text < 200 {
        return Err(format!("the UI panel shows no text ({text} light pixels)"));
    }
    Ok(())
}

fn region(image: &ImageData, xs: std::ops::Range<u32>, ys: std::ops::Range<u32>) -> Vec<[f32; 4]> {
    ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
        .map(|(x, y)| image.pixels[(y * image.width + x) as usize])
        .collect()
}

fn std_dev(values: impl Iterator<Item = f32> + Clone) -> f32 {
    let n = values.clone().count() as f32;
    let mean = values.clone().sum::<f32>() / n;
    (values.map(|v| (v - mean).powi(2)).sum::<f32>() / n).sqrt()
}
