//! The real renderer as a [`FrameSource`]: `lucid_passes::Renderer` on the loaded scene, driven by
//! the panels' settings and the fly camera.

use super::{FrameRequest, FrameSource};
use crate::settings::{Algorithm, Denoiser, RenderSettings};
use lucid_engine::graph::{Executor, ImageHandle, RenderGraph};
use lucid_engine::scene::Scene;
use lucid_engine::Context;
use lucid_passes::renderer::{self, Renderer, Settings};

/// Renders the loaded scene with the chosen algorithm and denoiser.
pub struct RendererSource {
    renderer: Renderer,
    name: String,
}

impl RendererSource {
    /// Uploads `scene` and prepares rendering at `extent`.
    pub fn new(ctx: &Context, scene: Scene, extent: [u32; 2]) -> anyhow::Result<Self> {
        let name = format!("{} renderer", scene.name);
        let renderer = Renderer::new(
            ctx,
            scene,
            extent[0].max(1),
            extent[1].max(1),
            Settings::default(),
        )?;
        Ok(Self { renderer, name })
    }
}

/// The renderer settings the panels describe (display settings are the app's own).
fn settings(base: &Settings, panel: &RenderSettings) -> Settings {
    Settings {
        algorithm: match panel.algorithm {
            Algorithm::PathTracing => renderer::Algorithm::PathTracing,
            Algorithm::Bidirectional => renderer::Algorithm::Bidirectional,
        },
        samples_per_pixel: panel.spp.max(1),
        max_depth: panel.max_depth.max(1),
        accumulate: panel.accumulate,
        denoiser: match panel.denoiser {
            Denoiser::None => renderer::Denoiser::None,
            Denoiser::Svgf => renderer::Denoiser::Svgf,
        },
        ..*base
    }
}

impl FrameSource for RendererSource {
    fn name(&self) -> &str {
        &self.name
    }

    fn render(
        &mut self,
        graph: &mut RenderGraph,
        request: &FrameRequest<'_>,
    ) -> anyhow::Result<ImageHandle> {
        self.renderer.resize(request.extent[0], request.extent[1])?;
        self.renderer.set_camera(*request.camera);
        let next = settings(self.renderer.settings(), request.settings);
        self.renderer.set_settings(next);
        let (images, _) = self.renderer.add_frame(graph);
        let [w, h] = request.extent;
        Ok(lucid_passes::debug_view::add(
            graph,
            &images,
            request.settings.view,
            w,
            h,
        ))
    }

    fn executor(&mut self) -> &mut Executor {
        self.renderer.executor_mut()
    }

    fn samples_accumulated(&self) -> u64 {
        u64::from(self.renderer.accumulated_frames())
            * u64::from(self.renderer.settings().samples_per_pixel)
    }
}
