//! `lucid view` (and `lucid` without arguments): the interactive sandbox window.

use super::size::Size;
use anyhow::Context as _;
use clap::Args;
use lucid_sandbox::{AppOptions, Screenshot, DEFAULT_SCENE};
use std::path::PathBuf;

/// Options of `lucid view`.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// A built-in scene name (see `lucid render --help`) or a `.gltf` / `.glb` file.
    #[arg(default_value = DEFAULT_SCENE)]
    scene: String,
    /// Initial window size.
    #[arg(long, default_value = "1280x720")]
    size: Size,
    /// Directory F12 captures are written to.
    #[arg(long, default_value = ".")]
    capture_dir: PathBuf,
    /// After N frames, save the window (UI included) as a PNG and exit.
    #[arg(long, num_args = 2, value_names = ["N", "FILE"])]
    screenshot_after: Option<Vec<String>>,
}

/// Opens the window.
pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    let screenshot = match args.screenshot_after.as_deref() {
        Some([frames, file]) => Some(Screenshot {
            after_frames: frames
                .parse()
                .ok()
                .filter(|&n: &u64| n > 0)
                .with_context(|| format!("--screenshot-after: {frames:?} is not a frame count"))?,
            path: PathBuf::from(file),
        }),
        _ => None,
    };
    lucid_sandbox::run(AppOptions {
        scene: args.scene.clone(),
        size: [args.size.width, args.size.height],
        capture_dir: args.capture_dir.clone(),
        screenshot,
    })
}
