//! How the sandbox was asked to start.

use super::settings::RenderSettings;
use std::path::PathBuf;

/// Read back the window after some frames, save it and exit.
///
/// ```
/// let shot = lucid_sandbox::Screenshot {
///     after_frames: 5,
///     path: "window.png".into(),
/// };
/// assert_eq!(shot.path.extension().unwrap(), "png");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Screenshot {
    /// The frame (counting from 1) to save.
    pub after_frames: u64,
    /// The PNG file to write.
    pub path: PathBuf,
}

/// Start-up options of the interactive sandbox.
///
/// ```
/// let options = lucid_sandbox::AppOptions {
///     scene: "scene.glb".into(), // or a built-in name such as lucid_sandbox::DEFAULT_SCENE
///     env: None,                  // or Some("sky.hdr".into())
///     size: [1280, 720],
///     capture_dir: "captures".into(),
///     screenshot: None,
/// };
/// # assert_eq!(options.size[0], 1280);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AppOptions {
    /// A built-in scene name or a `.gltf` / `.glb` file.
    pub scene: String,
    /// An equirectangular environment map (`.hdr` or `.exr`) lighting every scene opened.
    pub env: Option<PathBuf>,
    /// Initial window size in pixels.
    pub size: [u32; 2],
    /// Where F12 captures go.
    pub capture_dir: PathBuf,
    /// Take one screenshot and exit.
    pub screenshot: Option<Screenshot>,
}

/// How the window starts beyond [`AppOptions`]: the renderer configurations (the panels change
/// them later) and an optional self-test.
///
/// ```
/// use lucid_sandbox::{Algorithm, Denoiser, RenderSettings, Startup};
/// // `lucid view --split pt/none`: SVGF on the left, the raw estimate on the right.
/// let left = RenderSettings::default();
/// let startup = Startup {
///     render: left,
///     split: Some(RenderSettings {
///         denoiser: Denoiser::None,
///         ..left
///     }),
///     ..Startup::default()
/// };
/// assert_eq!(startup.split.unwrap().algorithm, Algorithm::PathTracing);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Startup {
    /// The configuration of the image (of its left half in a split view).
    pub render: RenderSettings,
    /// Start in the split view, with this configuration on the right half.
    pub split: Option<RenderSettings>,
    /// Over the first frames, shrink the window, report it minimized, restore it and report its
    /// surface lost, printing each step (a self-test of presentation; the screenshot, if any, fails
    /// unless every step was taken first).
    pub window_test: bool,
    /// Before the first frame, run the `--algo auto` calibration on the scene (the panel's goal:
    /// 60 frames per second, least DSSIM) and start with its choice.
    pub calibrate: bool,
}
