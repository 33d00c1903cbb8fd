//! The boundary between the app and whatever renders the scene: a [`FrameSource`] adds the passes
//! of one frame to the app's render graph and returns its HDR output. The app tone-maps it,
//! draws the UI over it and presents it.

mod renderer;
mod side_by_side;
mod split;
mod test_pattern;

pub use renderer::RendererSource;
pub use side_by_side::split_column;
pub use test_pattern::TestPatternSource;

use super::settings::RenderSettings;
use lucid_engine::graph::{Executor, ImageHandle, PassTiming, RenderGraph};
use lucid_engine::scene::Camera;
use lucid_passes::tradeoff::{Calibration, Choice, Goal};

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
    /// The right half's settings while the split view is on (the left half uses `settings`).
    pub split: Option<&'a RenderSettings>,
}

/// The numbers shown on one half of the split view.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SideStats {
    /// Samples per pixel accumulated.
    pub samples: u64,
    /// GPU milliseconds of the half's renderer in its last completed frame.
    pub gpu_ms: f64,
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

    /// The left and right halves' numbers while the output is a split view.
    fn split_stats(&self) -> Option<[SideStats; 2]> {
        None
    }

    /// Runs the `--algo auto` calibration on what the source renders (its frames in flight
    /// finished first) and picks a configuration for `goal`; an error for a source without a scene.
    fn calibrate(&mut self, _goal: Goal) -> anyhow::Result<(Calibration, Choice)> {
        anyhow::bail!("{} has no scene to calibrate on", self.name())
    }
}

/// GPU milliseconds of a renderer's passes among `timings`: the app's own passes (`sandbox.*`, the
/// window's `present.*` and the display's tone mapping) do not count.
pub fn renderer_ms(timings: &[PassTiming]) -> f64 {
    timings
        .iter()
        .filter(|t| {
            !t.name.starts_with("sandbox.")
                && !t.name.starts_with("present.")
                && t.name != "tonemap"
        })
        .map(|t| t.ms)
        .sum()
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod timing_tests {
    use super::*;

    #[test]
    fn renderer_time_leaves_out_the_apps_passes() {
        let timing = |name: &str, ms| PassTiming {
            name: name.into(),
            ms,
            start_ms: 0.0,
        };
        let timings = [
            timing("gbuffer", 1.0),
            timing("path_trace", 2.5),
            timing("sandbox.side_by_side", 0.25),
            timing("tonemap", 0.5),
            timing("sandbox.ui", 0.125),
            timing("present.copy_to_window", 0.0625),
        ];
        assert_eq!(renderer_ms(&timings), 3.5);
        assert_eq!(renderer_ms(&[]), 0.0);
    }
}
