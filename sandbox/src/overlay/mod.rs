//! The egui overlay: window input to egui, egui's output drawn onto the swapchain image in a
//! render graph pass.

mod render_pass;
mod targets;

use anyhow::Context as _;
use ash::vk;
use egui::epaint::ClippedPrimitive;
use egui_ash_renderer::{Options, Renderer, RendererError};
use lucid_engine::error::VkResultExt as _;
use lucid_engine::graph::{Access, ImageHandle, RenderGraph};
use lucid_engine::{Context, EngineError};
use std::cell::RefCell;
use std::rc::Rc;
use targets::Targets;
use winit::window::Window;

/// What one frame of UI draws.
#[derive(Clone)]
pub struct OverlayFrame {
    primitives: Rc<[ClippedPrimitive]>,
    pixels_per_point: f32,
}

/// egui's context, its window integration and its Vulkan renderer.
pub struct Overlay {
    egui: egui::Context,
    input: egui_winit::State,
    renderer: Rc<RefCell<Renderer>>,
    targets: Targets,
    upload_pool: vk::CommandPool,
    ctx: Context,
}

impl Overlay {
    /// An overlay for `window`, drawing into images of `format`.
    pub fn new(ctx: &Context, window: &Window, format: vk::Format) -> anyhow::Result<Self> {
        let egui = egui::Context::default();
        let input = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            window.theme(),
            None,
        );
        let targets = Targets::new(ctx, format)?;
        let renderer = Renderer::with_default_allocator(
            ctx.instance(),
            ctx.physical_device(),
            ctx.device().clone(),
            targets.render_pass(),
            Options {
                in_flight_frames: ctx.frames_in_flight(),
                enable_depth_test: false,
                enable_depth_write: false,
                srgb_framebuffer: false,
            },
        )
        .context("creating the egui renderer")?;
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.queue_family())
            .flags(
                vk::CommandPoolCreateFlags::TRANSIENT
                    | vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER,
            );
        // SAFETY: device valid.
        let upload_pool = unsafe { ctx.device().create_command_pool(&pool_info, None) }
            .vk("vkCreateCommandPool")?;
        Ok(Self {
            egui,
            input,
            renderer: Rc::new(RefCell::new(renderer)),
            targets,
            upload_pool,
            ctx: ctx.clone(),
        })
    }

    /// Passes a window event to egui; returns whether egui consumed it.
    pub fn on_window_event(&mut self, window: &Window, event: &winit::event::WindowEvent) -> bool {
        self.input.on_window_event(window, event).consumed
    }

    /// Whether egui wants keyboard input (a text field has focus).
    pub fn wants_keyboard(&self) -> bool {
        self.egui.wants_keyboard_input()
    }

    /// Whether the pointer is over egui.
    pub fn wants_pointer(&self) -> bool {
        self.egui.wants_pointer_input() || self.egui.is_pointer_over_area()
    }

    /// Makes framebuffers for the swapchain's image views (after every swapchain recreation); the
    /// GPU must be idle.
    pub fn set_targets(
        &mut self,
        format: vk::Format,
        views: &[vk::ImageView],
        extent: vk::Extent2D,
    ) -> anyhow::Result<()> {
        if self.targets.set(format, views, extent)? {
            self.renderer
                .borrow_mut()
                .set_render_pass(self.targets.render_pass())
                .context("rebuilding the egui pipeline for a new swapchain format")?;
        }
        Ok(())
    }

    /// Runs the UI code for one frame and uploads the textures it needs.
    pub fn run(
        &mut self,
        window: &Window,
        ui: impl FnMut(&egui::Context),
    ) -> anyhow::Result<OverlayFrame> {
        let raw_input = self.input.take_egui_input(window);
        let output = self.egui.run(raw_input, ui);
        self.input
            .handle_platform_output(window, output.platform_output);
        let textures = output.textures_delta;
        if !textures.set.is_empty() || !textures.free.is_empty() {
            // Frames in flight may sample the textures being replaced or freed.
            self.ctx.wait_idle()?;
            let mut renderer = self.renderer.borrow_mut();
            self.ctx
                .with_queue(|queue| renderer.set_textures(queue, self.upload_pool, &textures.set))
                .context("uploading egui textures")?;
            renderer
                .free_textures(&textures.free)
                .context("freeing egui textures")?;
        }
        let primitives = self.egui.tessellate(output.shapes, output.pixels_per_point);
        Ok(OverlayFrame {
            primitives: primitives.into(),
            pixels_per_point: output.pixels_per_point,
        })
    }

    /// Adds the pass drawing `frame` onto `target`, swapchain image `index`; returns the new
    /// version of `target`.
    pub fn add_pass(
        &self,
        graph: &mut RenderGraph,
        target: ImageHandle,
        index: u32,
        frame: OverlayFrame,
    ) -> anyhow::Result<ImageHandle> {
        let begin = self.targets.begin_info(index)?;
        let extent = begin.extent;
        let renderer = self.renderer.clone();
        let device = self.ctx.device().clone();
        let mut p = graph.add_pass("sandbox.ui");
        let target = p.write(target, Access::ColorAttachmentWrite);
        p.execute(move |pcx| {
            let cmd = pcx.command_buffer();
            // SAFETY: cmd is recording; the graph moved the image to COLOR_ATTACHMENT_OPTIMAL, the
            // layout the render pass starts and ends in.
            unsafe {
                device.cmd_begin_render_pass(cmd, &begin.info(), vk::SubpassContents::INLINE)
            };
            let drawn = renderer.borrow_mut().cmd_draw(
                cmd,
                extent,
                frame.pixels_per_point,
                &frame.primitives,
            );
            // SAFETY: the render pass begun above.
            unsafe { device.cmd_end_render_pass(cmd) };
            drawn.map_err(engine_error)
        });
        Ok(target)
    }
}

fn engine_error(e: RendererError) -> EngineError {
    match e {
        RendererError::Vulkan(result) => EngineError::Vulkan {
            call: "egui renderer",
            result,
        },
        other => EngineError::InvalidArgument(format!("egui renderer: {other}")),
    }
}

impl Drop for Overlay {
    fn drop(&mut self) {
        if let Err(e) = self.ctx.wait_idle() {
            tracing::error!("waiting for the GPU before destroying the overlay: {e}");
        }
        // SAFETY: the GPU is idle; the pool's command buffers have completed.
        unsafe {
            self.ctx
                .device()
                .destroy_command_pool(self.upload_pool, None)
        };
    }
}
