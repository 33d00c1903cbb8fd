//! A stand-in frame source until the light-transport renderer lands: the engine's test pattern,
//! animated by time and driven by the camera so that flying visibly changes the picture.

use super::{FrameRequest, FrameSource};
use crate::settings::RenderSettings;
use lucid_engine::graph::{Executor, ImageHandle, RenderGraph};
use lucid_engine::scene::Camera;
use lucid_engine::shader::ShaderLibrary;
use lucid_engine::Context;
use lucid_passes::debug::test_pattern;

/// The test pattern as a [`FrameSource`].
pub struct TestPatternSource {
    executor: Executor,
    accumulated: u64,
    last: Option<(Camera, RenderSettings, [u32; 2])>,
}

impl TestPatternSource {
    /// A source rendering on `ctx`.
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        Ok(Self {
            executor: Executor::new(ctx, ShaderLibrary::new(ctx, None)?)?,
            accumulated: 0,
            last: None,
        })
    }
}

impl FrameSource for TestPatternSource {
    fn name(&self) -> &str {
        "test pattern"
    }

    fn render(
        &mut self,
        graph: &mut RenderGraph,
        request: &FrameRequest<'_>,
    ) -> anyhow::Result<ImageHandle> {
        let state = (*request.camera, *request.settings, request.extent);
        if !request.settings.accumulate || self.last != Some(state) {
            self.accumulated = 0;
        }
        self.last = Some(state);
        self.accumulated += u64::from(request.settings.spp.get());
        let params = pattern_params(request);
        let [w, h] = request.extent;
        Ok(test_pattern::add_test_pattern(graph, w, h, &params).combined)
    }

    fn executor(&mut self) -> &mut Executor {
        &mut self.executor
    }

    fn samples_accumulated(&self) -> u64 {
        self.accumulated
    }
}

/// Gain pulses with time, the checker size follows the view direction and the offset follows
/// the camera height.
fn pattern_params(request: &FrameRequest<'_>) -> test_pattern::Params {
    let forward = request.camera.forward();
    let turn = forward.x.atan2(-forward.z) / std::f32::consts::PI;
    test_pattern::Params {
        gain: 1.0 + 0.5 * (request.time * 2.0).sin(),
        checker: 8 + (turn.abs() * 56.0) as u32,
        offset: (request.camera.position.y * 0.1).clamp(-0.5, 0.5),
        ..test_pattern::Params::default()
    }
}
