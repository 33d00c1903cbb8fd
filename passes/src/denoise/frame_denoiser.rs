//! The seam between the renderer and its denoisers: a denoiser plans each frame (whether it runs
//! and what the light transport must trace for it), then adds its passes over inputs the renderer
//! builds once from the light transport's outputs and the G-buffer. Each instance keeps its
//! history under its own key prefix, so two denoisers never share a history.
//!
//! A new denoiser is one module under `denoise/` implementing [`FrameDenoiser`], its shaders in
//! `shaders/<denoiser>/`, and one arm in the renderer's choice of denoiser.

use crate::denoise::gbuffer::GBuffer;
use crate::light_transport::{ReplayParams, SurfaceImages};
use crate::samples_per_pixel::SamplesPerPixel;
use lucid_engine::graph::{BufferHandle, ImageHandle, RenderGraph};

/// What the renderer knows of a frame before its light transport is traced.
#[derive(Clone, Copy, Debug)]
pub struct FrameInfo {
    /// The frame's index.
    pub frame_index: u32,
    /// Frames averaged into the accumulated image before this one (0: accumulation restarts).
    pub accumulated_frames: u32,
    /// Samples per pixel of this frame.
    pub samples_per_pixel: SamplesPerPixel,
    /// The scene or the light transport's settings changed since the last frame.
    pub scene_changed: bool,
    /// The light transport can replay last frame's paths (`shaders/common/replay.glsl`).
    pub replays_paths: bool,
}

/// What a denoiser asks of a frame's light transport, besides the surface images every denoiser
/// reads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TransportRequest {
    /// Side of the strata in which one pixel replays last frame's path (0: none).
    pub replay_stratum: u32,
}

/// Everything a denoiser reads of a frame.
#[derive(Clone, Copy, Debug)]
pub struct DenoiseInputs {
    /// This frame's noisy radiance.
    pub radiance: ImageHandle,
    /// The light transport's per-pixel first-hit images.
    pub surface: SurfaceImages,
    /// The accumulated output (this frame's radiance when nothing is accumulated).
    pub accumulated: ImageHandle,
    /// Frames averaged into `accumulated` before this one.
    pub accumulated_frames: u32,
    /// Whether the renderer accumulates frames while the view is still (`Settings::accumulate`).
    pub accumulating: bool,
    /// What the light transport replayed this frame ([`TransportRequest::replay_stratum`]).
    pub replay: ReplayParams,
    /// This frame's index.
    pub frame_index: u32,
    /// Primary visibility.
    pub gbuffer: GBuffer,
    /// Output width.
    pub width: u32,
    /// Output height.
    pub height: u32,
}

/// What a denoiser adds to a frame.
#[derive(Clone, Copy, Debug)]
pub struct Denoised {
    /// The image shown (`inputs.accumulated` when the denoiser left the frame as it was).
    pub image: ImageHandle,
    /// SVGF's temporal gradients, for the debug view; `None` for other denoisers.
    pub gradient: Option<ImageHandle>,
    /// The learned denoiser's per-pixel inputs (what `lucid dataset` records); `None` otherwise.
    pub record: Option<BufferHandle>,
}

impl Denoised {
    /// An image and nothing else.
    pub fn image(image: ImageHandle) -> Self {
        Self {
            image,
            gradient: None,
            record: None,
        }
    }
}

/// A denoiser the renderer runs after the light transport.
pub trait FrameDenoiser: Send {
    /// Called once per frame before the light transport is added: `None` when the denoiser does
    /// not run this frame (the accumulated image is shown and the surface images are not traced).
    fn plan(&mut self, frame: &FrameInfo) -> Option<TransportRequest>;

    /// Adds the denoiser's passes for the frame that [`FrameDenoiser::plan`] planned.
    fn add(&mut self, g: &mut RenderGraph, inputs: &DenoiseInputs) -> Denoised;

    /// History keys to drop when the scene changes (empty for a denoiser that detects the change
    /// itself, as SVGF does with its temporal gradients).
    fn reset_on_scene_change(&self) -> Vec<String>;
}
