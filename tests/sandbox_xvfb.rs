//! The interactive sandbox in a real window: under Xvfb (on lavapipe when there is no GPU, with
//! validation on) it starts, renders frames, saves a screenshot of the window by itself and exits
//! cleanly; the screenshot must show the scene and the UI panel.
//!
//! winit needs the main thread, so this test has its own `main` (`harness = false`): it starts
//! Xvfb, then runs itself again as the app process (`LUCID_SANDBOX_TEST_SHOT` set), and checks
//! that process's exit status, output and screenshot.

use lucid_engine::capture::{load_png, ImageData};
use lucid_sandbox::{AppOptions, Screenshot};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitCode, Output, Stdio};
use std::time::{Duration, Instant};

/// Set in the app process: where to write the screenshot.
const CHILD_VAR: &str = "LUCID_SANDBOX_TEST_SHOT";
const WIDTH: u32 = 800;
const HEIGHT: u32 = 600;
/// Frames before the screenshot.
const FRAMES: u64 = 5;
/// The app process must finish within this (lavapipe in a debug build is slow).
const APP_TIMEOUT: Duration = Duration::from_secs(300);

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
    let mut xvfb = Xvfb::start()?;
    let output = run_app(&xvfb.display, &shot);
    xvfb.stop();
    let output = output?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        return Err(format!(
            "the sandbox exited with {}:\n{stderr}",
            output.status
        ));
    }
    if stderr.contains("VUID") || stderr.to_lowercase().contains("validation message") {
        return Err(format!("validation reported problems:\n{stderr}"));
    }
    let image = load_png(&shot).map_err(|e| format!("reading the screenshot: {e}"))?;
    std::fs::remove_file(&shot).map_err(|e| e.to_string())?;
    check_screenshot(&image)
}

fn run_app(display: &str, shot: &Path) -> Result<Output, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let child = Command::new(exe)
        .env(CHILD_VAR, shot)
        .env("DISPLAY", display)
        .env_remove("WAYLAND_DISPLAY")
        .env("LUCID_VALIDATION", "1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("starting the app process: {e}"))?;
    wait_with_timeout(child, APP_TIMEOUT)
}

fn wait_with_timeout(mut child: Child, timeout: Duration) -> Result<Output, String> {
    let start = Instant::now();
    loop {
        match child.try_wait().map_err(|e| e.to_string())? {
            Some(_) => return child.wait_with_output().map_err(|e| e.to_string()),
            None if start.elapsed() > timeout => {
                let _ = child.kill();
                let output = child.wait_with_output().map_err(|e| e.to_string())?;
                return Err(format!(
                    "the sandbox did not exit within {timeout:?}:\n{}",
                    String::from_utf8_lossy(&output.stderr)
                ));
            }
            None => std::thread::sleep(Duration::from_millis(100)),
        }
    }
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

/// An Xvfb server on a free display, stopped on drop.
struct Xvfb {
    process: Option<Child>,
    display: String,
}

impl Xvfb {
    fn start() -> Result<Self, String> {
        for n in 90..140 {
            let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
            if socket.exists() || Path::new(&format!("/tmp/.X{n}-lock")).exists() {
                continue;
            }
            let mut process = Command::new("Xvfb")
                .arg(format!(":{n}"))
                .args(["-screen", "0", "1024x768x24", "-nolisten", "tcp"])
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .map_err(|e| {
                    format!("Xvfb is not installed ({e}): scripts/setup.sh installs it (apt-get install xvfb)")
                })?;
            let start = Instant::now();
            while start.elapsed() < Duration::from_secs(10) {
                if socket.exists() {
                    return Ok(Self {
                        process: Some(process),
                        display: format!(":{n}"),
                    });
                }
                if process.try_wait().map_err(|e| e.to_string())?.is_some() {
                    break;
                }
                std::thread::sleep(Duration::from_millis(50));
            }
            let _ = process.kill();
            let _ = process.wait();
        }
        Err("Xvfb could not start on any display from :90 to :139".into())
    }

    fn stop(&mut self) {
        if let Some(mut process) = self.process.take() {
            let _ = process.kill();
            let _ = process.wait();
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        self.stop();
    }
}
