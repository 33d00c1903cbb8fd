//! 2D images with one view, either owning their memory or bound into a shared (aliased) block.

use super::{allocate, free, FormatInfo, MemoryLocation, ResourceState};
use crate::context::{Context, Shared};
use crate::error::{EngineError, Result, VkResultExt};
use ash::vk;
use gpu_allocator::vulkan::Allocation;
use std::sync::{Arc, Mutex};

/// Size and format of a 2D image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ImageDesc {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Texel format.
    pub format: vk::Format,
}

impl ImageDesc {
    /// An image of `format`.
    pub fn new(width: u32, height: u32, format: vk::Format) -> Self {
        Self {
            width,
            height,
            format,
        }
    }

    /// RGBA 32-bit float.
    pub fn rgba32f(width: u32, height: u32) -> Self {
        Self::new(width, height, vk::Format::R32G32B32A32_SFLOAT)
    }

    /// RGBA 16-bit float.
    pub fn rgba16f(width: u32, height: u32) -> Self {
        Self::new(width, height, vk::Format::R16G16B16A16_SFLOAT)
    }

    /// One 32-bit float channel.
    pub fn r32f(width: u32, height: u32) -> Self {
        Self::new(width, height, vk::Format::R32_SFLOAT)
    }

    /// RGBA 8-bit unsigned normalised (linear).
    pub fn rgba8(width: u32, height: u32) -> Self {
        Self::new(width, height, vk::Format::R8G8B8A8_UNORM)
    }

    /// Bytes of tightly packed texel data (0 for formats Lucid does not know).
    pub fn byte_size(&self) -> u64 {
        FormatInfo::of(self.format).map_or(0, |f| f.bytes as u64)
            * self.width as u64
            * self.height as u64
    }

    /// The whole-image extent.
    pub fn extent(&self) -> vk::Extent3D {
        vk::Extent3D {
            width: self.width,
            height: self.height,
            depth: 1,
        }
    }
}

/// A 2D image and its view.
pub struct Image {
    shared: Arc<Shared>,
    raw: vk::Image,
    view: vk::ImageView,
    allocation: Option<(Allocation, &'static str)>,
    desc: ImageDesc,
    usage: vk::ImageUsageFlags,
    name: String,
    owned: bool,
    state: Mutex<ResourceState>,
}

impl Image {
    /// Creates an image without memory; bind it with [`Image::bind`] before use.
    pub fn unbound(
        ctx: &Context,
        name: &str,
        desc: ImageDesc,
        usage: vk::ImageUsageFlags,
    ) -> Result<Self> {
        if desc.width == 0 || desc.height == 0 {
            return Err(EngineError::InvalidArgument(format!(
                "image {name} has zero size ({}x{})",
                desc.width, desc.height
            )));
        }
        if FormatInfo::of(desc.format).is_none() {
            return Err(EngineError::InvalidArgument(format!(
                "image {name} uses format {:?}, which Lucid does not support",
                desc.format
            )));
        }
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(desc.format)
            .extent(desc.extent())
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: device valid; info complete.
        let raw = unsafe { ctx.device().create_image(&info, None) }.vk("vkCreateImage")?;
        ctx.set_name(raw, name);
        Ok(Self {
            shared: ctx.shared.clone(),
            raw,
            view: vk::ImageView::null(),
            allocation: None,
            desc,
            usage,
            name: name.to_string(),
            owned: true,
            state: Mutex::default(),
        })
    }

    /// Wraps an image (and view) the application owns, e.g. its own output image, to import it into
    /// a render graph. Lucid never destroys it; `state` is its layout and last access now.
    pub fn from_raw(
        ctx: &Context,
        name: &str,
        raw: vk::Image,
        view: vk::ImageView,
        desc: ImageDesc,
        usage: vk::ImageUsageFlags,
        state: ResourceState,
    ) -> Self {
        Self {
            shared: ctx.shared.clone(),
            raw,
            view,
            allocation: None,
            desc,
            usage,
            name: name.to_string(),
            owned: false,
            state: Mutex::new(state),
        }
    }

    /// The accesses and layout the render graph last left this image in.
    pub fn tracked_state(&self) -> ResourceState {
        *self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Records the state the image is left in (done by the render graph after each frame).
    pub fn set_tracked_state(&self, state: ResourceState) {
        *self.state.lock().unwrap_or_else(|p| p.into_inner()) = state;
    }

    /// Creates an image with its own device-local memory.
    pub fn new(
        ctx: &Context,
        name: &str,
        desc: ImageDesc,
        usage: vk::ImageUsageFlags,
        category: &'static str,
    ) -> Result<Self> {
        let mut image = Self::unbound(ctx, name, desc, usage)?;
        let allocation = allocate(
            ctx,
            name,
            category,
            image.memory_requirements(),
            MemoryLocation::GpuOnly,
            false,
        )?;
        // SAFETY: the allocation outlives the image (freed in Drop after the image is destroyed).
        let memory = unsafe { allocation.memory() };
        let bound = image.bind(ctx, memory, allocation.offset());
        image.allocation = Some((allocation, category));
        bound?;
        Ok(image)
    }

    /// What memory this image needs.
    pub fn memory_requirements(&self) -> vk::MemoryRequirements {
        // SAFETY: raw is a valid image.
        unsafe { self.shared.device.get_image_memory_requirements(self.raw) }
    }

    /// Binds the image to `memory` at `offset` (memory owned elsewhere, e.g. an aliasing block)
    /// and creates its view.
    pub fn bind(&mut self, ctx: &Context, memory: vk::DeviceMemory, offset: u64) -> Result<()> {
        let device = ctx.device();
        // SAFETY: the caller provides memory satisfying memory_requirements().
        unsafe { device.bind_image_memory(self.raw, memory, offset) }.vk("vkBindImageMemory")?;
        let view_info = vk::ImageViewCreateInfo::default()
            .image(self.raw)
            .view_type(vk::ImageViewType::TYPE_2D)
            .format(self.desc.format)
            .subresource_range(color_range());
        // SAFETY: the image is bound to memory.
        self.view =
            unsafe { device.create_image_view(&view_info, None) }.vk("vkCreateImageView")?;
        ctx.set_name(self.view, &self.name);
        Ok(())
    }

    /// The Vulkan image.
    pub fn raw(&self) -> vk::Image {
        self.raw
    }

    /// The image's view.
    pub fn view(&self) -> vk::ImageView {
        self.view
    }

    /// Size and format.
    pub fn desc(&self) -> ImageDesc {
        self.desc
    }

    /// The usage flags it was created with.
    pub fn usage(&self) -> vk::ImageUsageFlags {
        self.usage
    }

    /// Debug name.
    pub fn name(&self) -> &str {
        &self.name
    }
}

/// The single colour mip level and layer of a 2D image.
pub fn color_range() -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange {
        aspect_mask: vk::ImageAspectFlags::COLOR,
        base_mip_level: 0,
        level_count: 1,
        base_array_layer: 0,
        layer_count: 1,
    }
}

impl Drop for Image {
    fn drop(&mut self) {
        if !self.owned {
            return;
        }
        // SAFETY: the owner guarantees the GPU no longer uses the image.
        unsafe {
            if self.view != vk::ImageView::null() {
                self.shared.device.destroy_image_view(self.view, None);
            }
            self.shared.device.destroy_image(self.raw, None);
        }
        if let Some((allocation, category)) = self.allocation.take() {
            free(&self.shared, category, allocation);
        }
    }
}
