//! The split view's right half: a second `Renderer` on the same scene, with its own settings and
//! the app's camera. It runs on its own executor (a renderer owns its temporal history) and is
//! submitted before the app's frame, leaving the right half of its output in an image that the
//! app's graph imports. Both submissions go to the context's one queue, so the barrier the app's
//! graph derives from the image's tracked state orders its read after this write.

use super::renderer::{new_renderer, renderer_settings, samples_accumulated};
use super::side_by_side::{self, copy_columns, split_column};
use super::{renderer_ms, FrameRequest, SideStats};
use crate::settings::RenderSettings;
use ash::vk;
use lucid_engine::graph::{Access, RenderGraph};
use lucid_engine::memory::{Image, ImageDesc};
use lucid_engine::scene::Scene;
use lucid_engine::Context;
use lucid_passes::debug::debug_view;
use lucid_passes::renderer::Renderer;
use std::sync::Arc;

/// The renderer of the right half and the image it leaves its output in.
pub struct SplitRenderer {
    renderer: Renderer,
    output: Option<Arc<Image>>,
    ctx: Context,
}

impl SplitRenderer {
    /// Uploads `scene` for a second renderer at `extent`.
    pub fn new(ctx: &Context, scene: Scene, extent: [u32; 2]) -> anyhow::Result<Self> {
        Ok(Self {
            renderer: new_renderer(ctx, scene, extent)?,
            output: None,
            ctx: ctx.clone(),
        })
    }

    /// Renders and submits one frame of `settings` from the request's camera; returns the image
    /// whose right half (from [`split_column`]) holds it.
    pub fn render(
        &mut self,
        request: &FrameRequest<'_>,
        settings: &RenderSettings,
    ) -> anyhow::Result<Arc<Image>> {
        let [width, height] = request.extent;
        self.renderer.resize(width, height)?;
        self.renderer.set_camera(*request.camera);
        let next = renderer_settings(self.renderer.settings(), settings);
        self.renderer.set_settings(next)?;
        let output = self.output_image(request.extent)?;

        let mut graph = RenderGraph::new();
        let (images, _) = self.renderer.add_frame(&mut graph);
        let shown = debug_view::add_debug_view(&mut graph, &images, settings.view, width, height);
        let target = graph.import_image("sandbox.split_right", output.clone());
        let mut p = graph.add_pass("sandbox.split_copy");
        let src = p.read(shown, Access::TransferRead);
        let dst = p.write(target, Access::TransferWrite);
        p.side_effect();
        p.execute(move |pcx| copy_columns(pcx, src, dst, split_column(width)..width, height));
        let compiled = graph.compile()?;
        self.renderer.executor_mut().execute(compiled)?;
        Ok(output)
    }

    /// The image for `extent`, made anew when the size changes (frames in flight keep the old one).
    fn output_image(&mut self, extent: [u32; 2]) -> anyhow::Result<Arc<Image>> {
        let desc = ImageDesc::new(extent[0], extent[1], side_by_side::FORMAT);
        match &self.output {
            Some(image) if image.desc() == desc => Ok(image.clone()),
            _ => {
                // Only transfers touch it, but every engine image has a view, which needs one of
                // the view usages.
                let usage = vk::ImageUsageFlags::TRANSFER_SRC
                    | vk::ImageUsageFlags::TRANSFER_DST
                    | vk::ImageUsageFlags::SAMPLED;
                let image = Arc::new(Image::new(
                    &self.ctx,
                    "sandbox.split_right",
                    desc,
                    usage,
                    "sandbox",
                )?);
                self.output = Some(image.clone());
                Ok(image)
            }
        }
    }

    /// Samples accumulated and GPU time of the right half.
    pub fn stats(&self) -> SideStats {
        SideStats {
            samples: samples_accumulated(&self.renderer),
            gpu_ms: renderer_ms(self.renderer.executor().pass_timings()),
        }
    }
}
