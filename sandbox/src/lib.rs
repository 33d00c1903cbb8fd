//! `lucid_sandbox`: the interactive sandbox behind `lucid` and `lucid view`: a window showing the
//! frame source's output through a fly camera, with egui panels for the scene, renderer and display
//! settings and live statistics, and a split view comparing two configurations. The window's
//! swapchain and display passes are `lucid_present`'s, which applications embedding Lucid use
//! without the app (see the `game_loop` example).
//!
//! ```no_run
//! use lucid_sandbox::{AppOptions, RenderSettings, Startup};
//! let options = AppOptions {
//!     scene: lucid_sandbox::DEFAULT_SCENE.into(),
//!     env: None,
//!     size: [1280, 720],
//!     capture_dir: ".".into(),
//!     screenshot: None,
//! };
//! let left = RenderSettings::default();
//! let startup = Startup {
//!     render: left,
//!     split: Some(left.compared()), // the other algorithm on the right half
//!     window_test: false,
//!     calibrate: false,
//! };
//! lucid_sandbox::run_with(options, startup)?;
//! # anyhow::Ok(())
//! ```
//!
//! The renderer plugs in through `frame_source::FrameSource`: Lucid's renderer on the loaded scene
//! (two of them side by side in the split view), or the engine's test pattern while no scene could
//! be loaded.

mod auto;
mod camera;
mod capture;
mod compose;
mod frame;
mod frame_source;
mod handler;
mod input;
mod options;
mod overlay;
mod pending;
mod scene;
mod session;
mod settings;
mod state;
mod stats;
mod ui;
mod window_test;

pub use options::{AppOptions, Screenshot, Startup};
pub use scene::DEFAULT_SCENE;
pub use settings::{
    Algorithm, Denoiser, DisplaySettings, EdgeEmission, RenderSettings, SamplesPerPixel, ToneCurve,
};

use anyhow::Context as _;
use lucid_engine::Validation;
use winit::event_loop::EventLoop;

/// The one-line explanation when there is no display to open the window on.
const NO_DISPLAY: &str =
    "no display found (DISPLAY/WAYLAND_DISPLAY unset): use `lucid render` for headless output";

/// Opens the sandbox window with the default renderer settings and runs until it is closed (or the
/// screenshot is taken). Fails when there is no display, on errors the app cannot show, and when
/// validation is on and reported anything.
///
/// ```no_run
/// // `lucid view classroom --screenshot-after 30 shot.png`
/// lucid_sandbox::run(lucid_sandbox::AppOptions {
///     scene: "classroom".into(),
///     env: None,
///     size: [800, 600],
///     capture_dir: std::env::temp_dir(),
///     screenshot: Some(lucid_sandbox::Screenshot {
///         after_frames: 30,
///         path: "shot.png".into(),
///     }),
/// })?;
/// # anyhow::Ok(())
/// ```
pub fn run(options: AppOptions) -> anyhow::Result<()> {
    run_with(options, Startup::default())
}

/// Like [`run`], starting with the renderer configurations of `startup` (e.g. in the split view;
/// see the crate's example).
pub fn run_with(options: AppOptions, startup: Startup) -> anyhow::Result<()> {
    anyhow::ensure!(lucid_present::display_available(), NO_DISPLAY);
    let event_loop = EventLoop::new().map_err(|e| {
        anyhow::anyhow!("cannot open the display ({e}): use `lucid render` for headless output")
    })?;
    let mut app = handler::App::new(options, startup);
    let ran = event_loop.run_app(&mut app);
    let (result, ctx) = app.finish();
    ran.context("the window event loop failed")?;
    result?;
    let Some(ctx) = ctx else {
        return Ok(());
    };
    let report = ctx.validation_log().take_report();
    if let Some(report) = report.filter(|_| ctx.validation() != Validation::Off) {
        anyhow::bail!(report);
    }
    Ok(())
}
