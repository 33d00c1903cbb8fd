//! The swapchain: created for the window's size, recreated (by its presenter's decision) on
//! resizes, out-of-date or suboptimal reports and lost surfaces, and absent while the surface has
//! zero size. Its images are wrapped as engine images so that a render graph can import them.

use crate::{vk_error, WindowSurface};
use anyhow::{bail, Context as _};
use ash::vk;
use lucid_engine::memory::{color_range, Image, ImageDesc, ResourceState};
use lucid_engine::Context;
use std::sync::Arc;
use winit::window::Window;

/// Formats the app can draw into and read back, in order of preference (UNORM: the tone-mapping
/// pass encodes sRGB itself).
const FORMATS: [vk::Format; 2] = [vk::Format::B8G8R8A8_UNORM, vk::Format::R8G8B8A8_UNORM];

/// What the app does with swapchain images.
const REQUIRED_USAGE: vk::ImageUsageFlags = vk::ImageUsageFlags::from_raw(
    vk::ImageUsageFlags::COLOR_ATTACHMENT.as_raw() | vk::ImageUsageFlags::TRANSFER_DST.as_raw(),
);

/// The swapchain and everything sized with it.
pub struct Swapchain {
    loader: ash::khr::swapchain::Device,
    raw: vk::SwapchainKHR,
    format: vk::Format,
    extent: vk::Extent2D,
    images: Vec<Arc<Image>>,
    views: Vec<vk::ImageView>,
    /// One per image: signalled by the frame that drew it, waited on by its presentation.
    render_finished: Vec<vk::Semaphore>,
    surface: WindowSurface,
    ctx: Context,
}

impl Swapchain {
    /// A swapchain for `surface`, sized to `size` when the surface leaves the size to us.
    pub(crate) fn new(
        ctx: &Context,
        surface: WindowSurface,
        size: [u32; 2],
    ) -> anyhow::Result<Self> {
        let mut swapchain = Self {
            loader: ash::khr::swapchain::Device::new(ctx.instance(), ctx.device()),
            raw: vk::SwapchainKHR::null(),
            format: vk::Format::UNDEFINED,
            extent: vk::Extent2D::default(),
            images: Vec::new(),
            views: Vec::new(),
            render_finished: Vec::new(),
            surface,
            ctx: ctx.clone(),
        };
        swapchain.recreate(size)?;
        Ok(swapchain)
    }

    /// Whether there are images to render to (false while the window has zero size).
    pub fn is_usable(&self) -> bool {
        self.raw != vk::SwapchainKHR::null()
    }

    /// The image format.
    pub fn format(&self) -> vk::Format {
        self.format
    }

    /// The image size.
    pub fn extent(&self) -> vk::Extent2D {
        self.extent
    }

    /// The images, as engine images for graph imports.
    pub(crate) fn images(&self) -> &[Arc<Image>] {
        &self.images
    }

    /// The images' views.
    pub fn views(&self) -> &[vk::ImageView] {
        &self.views
    }

    /// The semaphore the frame drawing image `index` signals.
    pub(crate) fn render_finished(&self, index: u32) -> vk::Semaphore {
        self.render_finished[index as usize]
    }

    /// Recreates the swapchain for the window's `size`; the GPU must be idle. Leaves it unusable
    /// (no images) when the surface or the window has zero size.
    pub(crate) fn recreate(&mut self, size: [u32; 2]) -> anyhow::Result<()> {
        let (physical, surface) = (self.ctx.physical_device(), self.surface.raw());
        let loader = self.surface.loader();
        // SAFETY: physical device and surface belong to the context's instance.
        let caps = unsafe { loader.get_physical_device_surface_capabilities(physical, surface) }
            .map_err(vk_error("vkGetPhysicalDeviceSurfaceCapabilitiesKHR"))?;
        let extent = if caps.current_extent.width == u32::MAX {
            vk::Extent2D {
                width: size[0].clamp(caps.min_image_extent.width, caps.max_image_extent.width),
                height: size[1].clamp(caps.min_image_extent.height, caps.max_image_extent.height),
            }
        } else {
            caps.current_extent
        };
        if extent.width == 0 || extent.height == 0 || size[0] == 0 || size[1] == 0 {
            self.destroy();
            return Ok(());
        }
        if !caps.supported_usage_flags.contains(REQUIRED_USAGE) {
            bail!(
                "the window surface does not support {REQUIRED_USAGE:?} (it offers {:?})",
                caps.supported_usage_flags
            );
        }
        let usage =
            REQUIRED_USAGE | (caps.supported_usage_flags & vk::ImageUsageFlags::TRANSFER_SRC);
        let format = self.choose_format()?;
        let mode = self.choose_present_mode()?;
        let count = if caps.max_image_count == 0 {
            caps.min_image_count + 1
        } else {
            (caps.min_image_count + 1).min(caps.max_image_count)
        };
        let alpha = [
            vk::CompositeAlphaFlagsKHR::OPAQUE,
            vk::CompositeAlphaFlagsKHR::INHERIT,
            vk::CompositeAlphaFlagsKHR::PRE_MULTIPLIED,
            vk::CompositeAlphaFlagsKHR::POST_MULTIPLIED,
        ]
        .into_iter()
        .find(|&a| caps.supported_composite_alpha.contains(a))
        .unwrap_or(vk::CompositeAlphaFlagsKHR::OPAQUE);
        let old = self.raw;
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(surface)
            .min_image_count(count)
            .image_format(format)
            .image_color_space(vk::ColorSpaceKHR::SRGB_NONLINEAR)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(usage)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(alpha)
            .present_mode(mode)
            .clipped(true)
            .old_swapchain(old);
        // SAFETY: the surface is valid; the old swapchain (if any) is idle.
        let created = unsafe { self.loader.create_swapchain(&info, None) };
        self.destroy();
        self.raw = created.map_err(vk_error("vkCreateSwapchainKHR"))?;
        self.ctx.set_name(self.raw, "window swapchain");
        self.format = format;
        self.extent = extent;
        self.wrap_images(usage)
            .context("setting up the swapchain images")
    }

    fn wrap_images(&mut self, usage: vk::ImageUsageFlags) -> anyhow::Result<()> {
        let device = self.ctx.device();
        // SAFETY: the swapchain was just created.
        let raws = unsafe { self.loader.get_swapchain_images(self.raw) }
            .map_err(vk_error("vkGetSwapchainImagesKHR"))?;
        let desc = ImageDesc::new(self.extent.width, self.extent.height, self.format);
        for (i, &raw) in raws.iter().enumerate() {
            let view_info = vk::ImageViewCreateInfo::default()
                .image(raw)
                .view_type(vk::ImageViewType::TYPE_2D)
                .format(self.format)
                .subresource_range(color_range());
            // SAFETY: the image belongs to the swapchain.
            let view = unsafe { device.create_image_view(&view_info, None) }
                .map_err(vk_error("vkCreateImageView"))?;
            self.views.push(view);
            // SAFETY: device valid.
            let semaphore =
                unsafe { device.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }
                    .map_err(vk_error("vkCreateSemaphore"))?;
            self.render_finished.push(semaphore);
            let name = format!("swapchain image {i}");
            self.ctx.set_name(raw, &name);
            self.images.push(Arc::new(Image::from_raw(
                &self.ctx,
                &name,
                raw,
                view,
                desc,
                usage,
                ResourceState::default(),
            )));
        }
        Ok(())
    }

    fn choose_format(&self) -> anyhow::Result<vk::Format> {
        let (physical, surface) = (self.ctx.physical_device(), self.surface.raw());
        // SAFETY: physical device and surface belong to the context's instance.
        let formats = unsafe {
            self.surface
                .loader()
                .get_physical_device_surface_formats(physical, surface)
        }
        .map_err(vk_error("vkGetPhysicalDeviceSurfaceFormatsKHR"))?;
        FORMATS
            .into_iter()
            .find(|f| {
                formats
                    .iter()
                    .any(|s| s.format == *f && s.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR)
            })
            .with_context(|| {
                format!("the window offers none of the formats {FORMATS:?} (it offers {formats:?})")
            })
    }

    fn choose_present_mode(&self) -> anyhow::Result<vk::PresentModeKHR> {
        let (physical, surface) = (self.ctx.physical_device(), self.surface.raw());
        // SAFETY: physical device and surface belong to the context's instance.
        let modes = unsafe {
            self.surface
                .loader()
                .get_physical_device_surface_present_modes(physical, surface)
        }
        .map_err(vk_error("vkGetPhysicalDeviceSurfacePresentModesKHR"))?;
        Ok(if modes.contains(&vk::PresentModeKHR::MAILBOX) {
            vk::PresentModeKHR::MAILBOX
        } else {
            vk::PresentModeKHR::FIFO
        })
    }

    /// Acquires the next image, signalling `semaphore` when it is ready: its index and whether the
    /// swapchain is suboptimal, or Vulkan's error (which `SurfaceState::acquired` interprets).
    pub(crate) fn acquire(&self, semaphore: vk::Semaphore) -> Result<(u32, bool), vk::Result> {
        // SAFETY: the swapchain is valid and the semaphore unsignalled with no pending operation.
        unsafe {
            self.loader
                .acquire_next_image(self.raw, 1_000_000_000, semaphore, vk::Fence::null())
        }
        .inspect_err(|&result| self.observe("vkAcquireNextImageKHR", result))
    }

    /// Marks the context's device lost when presenting reported it, as the engine's own calls do:
    /// every later submission and wait fails at once with the device-loss error.
    fn observe(&self, call: &'static str, result: vk::Result) {
        if result == vk::Result::ERROR_DEVICE_LOST {
            self.ctx.observe(vk_error(call)(result));
        }
    }

    /// Presents image `index` after its frame signalled [`Self::render_finished`]: whether the
    /// swapchain is suboptimal, or Vulkan's error (which `SurfaceState::presented` interprets).
    pub(crate) fn present(&self, index: u32) -> Result<bool, vk::Result> {
        let waits = [self.render_finished(index)];
        let swapchains = [self.raw];
        let indices = [index];
        let info = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&swapchains)
            .image_indices(&indices);
        // SAFETY: the image was acquired and its frame submitted with the semaphore to signal.
        self.ctx
            .with_queue(|queue| unsafe { self.loader.queue_present(queue, &info) })
            .inspect_err(|&result| self.observe("vkQueuePresentKHR", result))
    }

    /// Replaces a lost surface with a new one for `window`, destroying the swapchain (recreate it
    /// next); waits for the GPU first.
    pub(crate) fn replace_surface(&mut self, window: &Window) -> anyhow::Result<()> {
        tracing::warn!("the window surface was lost; creating a new one");
        self.ctx.wait_idle()?;
        self.destroy();
        self.surface.recreate(window)
    }

    /// Destroys the swapchain and what is sized with it; the GPU must be idle.
    fn destroy(&mut self) {
        let device = self.ctx.device();
        self.images.clear();
        // SAFETY: the GPU is idle: no frame uses the views or semaphores.
        unsafe {
            for view in self.views.drain(..) {
                device.destroy_image_view(view, None);
            }
            for semaphore in self.render_finished.drain(..) {
                device.destroy_semaphore(semaphore, None);
            }
            if self.raw != vk::SwapchainKHR::null() {
                self.loader.destroy_swapchain(self.raw, None);
            }
        }
        self.raw = vk::SwapchainKHR::null();
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        if let Err(e) = self.ctx.wait_idle() {
            tracing::error!("waiting for the GPU before destroying the swapchain: {e}");
        }
        self.destroy();
    }
}
