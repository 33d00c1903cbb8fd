//! The UI render pass and one framebuffer per swapchain image, remade with the swapchain.

use super::render_pass;
use anyhow::Context as _;
use ash::vk;
use lucid_engine::error::VkResultExt as _;
use lucid_engine::Context;

/// Where one frame's UI is drawn (plain handles, so a graph pass can own it).
#[derive(Clone, Copy)]
pub struct BeginTarget {
    render_pass: vk::RenderPass,
    framebuffer: vk::Framebuffer,
    /// The framebuffer size.
    pub extent: vk::Extent2D,
}

impl BeginTarget {
    /// The render pass begin info (no clears: the attachment is loaded).
    pub fn info(&self) -> vk::RenderPassBeginInfo<'static> {
        vk::RenderPassBeginInfo::default()
            .render_pass(self.render_pass)
            .framebuffer(self.framebuffer)
            .render_area(vk::Rect2D {
                offset: vk::Offset2D::default(),
                extent: self.extent,
            })
    }
}

/// The render pass and framebuffers for the current swapchain.
pub struct Targets {
    format: vk::Format,
    render_pass: vk::RenderPass,
    framebuffers: Vec<vk::Framebuffer>,
    extent: vk::Extent2D,
    ctx: Context,
}

impl Targets {
    /// A render pass for `format`, without framebuffers yet.
    pub fn new(ctx: &Context, format: vk::Format) -> anyhow::Result<Self> {
        Ok(Self {
            format,
            render_pass: render_pass::create(ctx, format)?,
            framebuffers: Vec::new(),
            extent: vk::Extent2D::default(),
            ctx: ctx.clone(),
        })
    }

    /// The render pass.
    pub fn render_pass(&self) -> vk::RenderPass {
        self.render_pass
    }

    /// Remakes the framebuffers for `views` (and the render pass when `format` changed, which the
    /// return value reports); the GPU must be idle.
    pub fn set(
        &mut self,
        format: vk::Format,
        views: &[vk::ImageView],
        extent: vk::Extent2D,
    ) -> anyhow::Result<bool> {
        self.destroy_framebuffers();
        let new_pass = format != self.format;
        if new_pass {
            let render_pass = render_pass::create(&self.ctx, format)?;
            // SAFETY: the GPU is idle; no framebuffer uses the old pass.
            unsafe {
                self.ctx
                    .device()
                    .destroy_render_pass(self.render_pass, None)
            };
            self.render_pass = render_pass;
            self.format = format;
        }
        for &view in views {
            let attachments = [view];
            let info = vk::FramebufferCreateInfo::default()
                .render_pass(self.render_pass)
                .attachments(&attachments)
                .width(extent.width)
                .height(extent.height)
                .layers(1);
            // SAFETY: the view is a live swapchain image view of `format`.
            let framebuffer = unsafe { self.ctx.device().create_framebuffer(&info, None) }
                .vk("vkCreateFramebuffer")?;
            self.framebuffers.push(framebuffer);
        }
        self.extent = extent;
        Ok(new_pass)
    }

    /// Where to draw on swapchain image `index`.
    pub fn begin_info(&self, index: u32) -> anyhow::Result<BeginTarget> {
        let framebuffer = *self
            .framebuffers
            .get(index as usize)
            .with_context(|| format!("no UI framebuffer for swapchain image {index}"))?;
        Ok(BeginTarget {
            render_pass: self.render_pass,
            framebuffer,
            extent: self.extent,
        })
    }

    fn destroy_framebuffers(&mut self) {
        for framebuffer in self.framebuffers.drain(..) {
            // SAFETY: callers keep the GPU idle while framebuffers change or drop.
            unsafe { self.ctx.device().destroy_framebuffer(framebuffer, None) };
        }
    }
}

impl Drop for Targets {
    fn drop(&mut self) {
        self.destroy_framebuffers();
        // SAFETY: the overlay waited for the GPU before dropping.
        unsafe {
            self.ctx
                .device()
                .destroy_render_pass(self.render_pass, None)
        };
    }
}
