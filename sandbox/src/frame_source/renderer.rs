//! The real renderer as a [`FrameSource`]: `lucid_passes::Renderer` on the loaded scene, driven by
//! the panels' settings and the fly camera; with a split view, a second renderer draws the right
//! half.

use super::split::SplitRenderer;
use super::{renderer_ms, side_by_side, FrameRequest, FrameSource, SideStats};
use crate::settings::RenderSettings;
use lucid_engine::graph::{Executor, ImageHandle, RenderGraph};
use lucid_engine::scene::Scene;
use lucid_engine::Context;
use lucid_passes::renderer::{Renderer, Settings};
use lucid_passes::tradeoff::{calibrate, Calibration, CalibrationOptions, Choice, Goal};

/// Renders the loaded scene with the chosen algorithm and denoiser.
pub struct RendererSource {
    renderer: Renderer,
    /// The right half's renderer while the split view is on.
    split: Option<SplitRenderer>,
    name: String,
}

impl RendererSource {
    /// Uploads `scene` and prepares rendering at `extent`.
    pub fn new(ctx: &Context, scene: Scene, extent: [u32; 2]) -> anyhow::Result<Self> {
        let name = format!("{} renderer", scene.name);
        Ok(Self {
            renderer: new_renderer(ctx, scene, extent)?,
            split: None,
            name,
        })
    }
}

/// A renderer of `scene` at `extent` (at least 1x1) with default settings; the panels' settings
/// are applied before each frame.
pub fn new_renderer(ctx: &Context, scene: Scene, extent: [u32; 2]) -> anyhow::Result<Renderer> {
    Ok(Renderer::new(
        ctx,
        scene,
        extent[0].max(1),
        extent[1].max(1),
        Settings::default(),
    )?)
}

/// The renderer settings the panels describe (display settings are the app's own).
pub fn renderer_settings(base: &Settings, panel: &RenderSettings) -> Settings {
    Settings {
        algorithm: panel.algorithm,
        samples_per_pixel: panel.spp,
        max_depth: panel.max_depth.max(1),
        bdpt_connections: panel.bdpt_connections,
        bdpt_mis: panel.bdpt_mis,
        bdpt_connection_roulette: panel.bdpt_connection_roulette,
        accumulate: panel.accumulate,
        denoiser: panel.denoiser,
        edge_emission: panel.edge_emission,
        svgf: panel.svgf,
        neural: panel.neural,
        ..*base
    }
}

/// Samples per pixel in a renderer's current output.
pub fn samples_accumulated(renderer: &Renderer) -> u64 {
    u64::from(renderer.accumulated_frames())
        * u64::from(renderer.settings().samples_per_pixel.get())
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
        let next = renderer_settings(self.renderer.settings(), request.settings);
        self.renderer.set_settings(next)?;
        let (images, _) = self.renderer.add_frame(graph);
        let [w, h] = request.extent;
        let shown = lucid_passes::debug::debug_view::add_debug_view(
            graph,
            &images,
            request.settings.view,
            w,
            h,
        );
        let Some(right_settings) = request.split else {
            self.split = None;
            return Ok(shown);
        };
        let split = match &mut self.split {
            Some(split) => split,
            None => {
                let ctx = self.renderer.executor().context().clone();
                let scene = self.renderer.scene().clone();
                self.split
                    .insert(SplitRenderer::new(&ctx, scene, request.extent)?)
            }
        };
        let right = split.render(request, right_settings)?;
        let right = graph.import_image("sandbox.split_right", right);
        Ok(side_by_side::add(graph, shown, right, request.extent))
    }

    fn executor(&mut self) -> &mut Executor {
        self.renderer.executor_mut()
    }

    fn samples_accumulated(&self) -> u64 {
        samples_accumulated(&self.renderer)
    }

    fn calibrate(&mut self, goal: Goal) -> anyhow::Result<(Calibration, Choice)> {
        let options = CalibrationOptions::for_device(self.renderer.executor().context());
        let calibration = calibrate(&mut self.renderer, &options, &mut || {})?;
        let choice = calibration.choose(goal)?;
        Ok((calibration, choice))
    }

    fn split_stats(&self) -> Option<[SideStats; 2]> {
        let left = SideStats {
            samples: samples_accumulated(&self.renderer),
            gpu_ms: renderer_ms(self.renderer.executor().pass_timings()),
        };
        self.split.as_ref().map(|right| [left, right.stats()])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lucid_passes::light_transport::bdpt::MisHeuristic;
    use lucid_passes::renderer::{Algorithm, Denoiser, EdgeEmission, SamplesPerPixel};

    #[test]
    fn the_panels_settings_reach_the_renderer() {
        let panel = RenderSettings {
            algorithm: Algorithm::Bidirectional,
            spp: SamplesPerPixel::new(3).unwrap(),
            max_depth: 5,
            bdpt_connections: std::num::NonZeroU32::new(3).unwrap(),
            bdpt_mis: MisHeuristic::Balance,
            bdpt_connection_roulette: 0.5,
            denoiser: Denoiser::Neural,
            edge_emission: EdgeEmission::Off,
            accumulate: false,
            ..RenderSettings::default()
        };
        let base = Settings {
            seed: 7,
            ..Settings::default()
        };
        let settings = renderer_settings(&base, &panel);
        assert_eq!(settings.algorithm, Algorithm::Bidirectional);
        assert_eq!(settings.samples_per_pixel.get(), 3);
        assert_eq!(settings.max_depth, 5);
        assert_eq!(settings.bdpt_connections.get(), 3);
        assert_eq!(settings.bdpt_mis, MisHeuristic::Balance);
        assert_eq!(settings.bdpt_connection_roulette, 0.5);
        assert_eq!(settings.denoiser, Denoiser::Neural);
        assert_eq!(settings.edge_emission, EdgeEmission::Off);
        assert!(!settings.accumulate);
        assert_eq!(settings.seed, 7, "what the panels do not set stays");
    }
}
