//! The boundary between the app and whatever renders the scene: a [`FrameSource`] adds the passes
//! of one frame to the app's render graph and returns its HDR output. The app tone-maps it,
//! draws the UI over it and presents it.

mod renderer;
mod test_pattern;

pub use renderer::RendererSource;
pub use test_pattern::TestPatternSource;

use super::settings::RenderSettings;
use lucid_engine::graph::{Executor, ImageHandle, RenderGraph};
use lucid_engine::scene::Camera;

/// Everything a frame source is asked to render one frame with.
#[derive(Clone, Copy, Debug)]
pub struct FrameRequest<'a> {
    /// The camera.
    pub camera: &'a Camera,
    /// Algorithm, samples, path length, denoiser, accumulation.
    pub settings: &'a RenderSettings,
    /// Output size in pixels (never zero).
    pub extent: [u32; 2],
    /// Seconds since the app started (for animated content).
    pub time: f32,
}

/// Renders the scene into an HDR image each frame.
pub trait FrameSource {
    /// A short name for the panels.
    fn name(&self) -> &str;

    /// Adds this frame's passes to `graph` and returns the linear HDR output (any float format,
    /// `request.extent` in size); the app reads it with `Access::ComputeSampled` and, for captures,
    /// `Access::TransferWrite` then `Access::TransferRead` (an imported image needs those usages).
    fn render(
        &mut self,
        graph: &mut RenderGraph,
        request: &FrameRequest<'_>,
    ) -> anyhow::Result<ImageHandle>;

    /// The executor the app runs each frame's graph on (the source owns it, as the renderer
    /// owns its executor with its temporal history).
    fn executor(&mut self) -> &mut Executor;

    /// Samples per pixel accumulated in the current output.
    fn samples_accumulated(&self) -> u64;
}
