//! Buffers: device-local, upload (host-visible) and readback, with staging uploads and reads.

use super::{allocate, free, MemoryLocation, ResourceState};
use crate::context::{Context, Shared};
use crate::error::{EngineError, Result, VkResultExt};
use ash::vk;
use gpu_allocator::vulkan::Allocation;
use std::sync::{Arc, Mutex};

/// How to create a buffer.
#[derive(Clone, Debug)]
pub struct BufferDesc {
    /// Debug name.
    pub name: String,
    /// Size in bytes (at least 1).
    pub size: u64,
    /// Vulkan usage flags.
    pub usage: vk::BufferUsageFlags,
    /// Where the memory lives (GPU only, CPU to GPU, GPU to CPU).
    pub location: MemoryLocation,
    /// The memory-report category (e.g. `scene`, `graph.transient`).
    pub category: &'static str,
}

/// A buffer with its memory.
pub struct Buffer {
    shared: Arc<Shared>,
    raw: vk::Buffer,
    allocation: Option<Allocation>,
    size: u64,
    usage: vk::BufferUsageFlags,
    location: MemoryLocation,
    category: &'static str,
    name: String,
    state: Mutex<ResourceState>,
}

impl Buffer {
    /// Creates a buffer with its own memory.
    pub fn new(ctx: &Context, desc: &BufferDesc) -> Result<Self> {
        if desc.size == 0 {
            return Err(EngineError::InvalidArgument(format!(
                "buffer {} has size 0",
                desc.name
            )));
        }
        let device = ctx.device();
        let info = vk::BufferCreateInfo::default()
            .size(desc.size)
            .usage(desc.usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: device is valid; info is complete.
        let raw = unsafe { device.create_buffer(&info, None) }.vk("vkCreateBuffer")?;
        // SAFETY: raw was just created.
        let requirements = unsafe { device.get_buffer_memory_requirements(raw) };
        let allocation = match allocate(
            ctx,
            &desc.name,
            desc.category,
            requirements,
            desc.location,
            true,
        ) {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: raw is unused.
                unsafe { device.destroy_buffer(raw, None) };
                return Err(e);
            }
        };
        // SAFETY: the allocation satisfies the buffer's requirements.
        if let Err(e) =
            unsafe { device.bind_buffer_memory(raw, allocation.memory(), allocation.offset()) }
                .vk("vkBindBufferMemory")
        {
            free(&ctx.shared, desc.category, allocation);
            // SAFETY: raw is unused.
            unsafe { device.destroy_buffer(raw, None) };
            return Err(e);
        }
        ctx.set_name(raw, &desc.name);
        Ok(Self {
            shared: ctx.shared.clone(),
            raw,
            allocation: Some(allocation),
            size: desc.size,
            usage: desc.usage,
            location: desc.location,
            category: desc.category,
            name: desc.name.clone(),
            state: Mutex::default(),
        })
    }

    /// Creates a buffer without memory (for aliasing), with its memory requirements; bind it with
    /// [`Buffer::bind`] before use.
    pub fn unbound(ctx: &Context, desc: &BufferDesc) -> Result<(Self, vk::MemoryRequirements)> {
        if desc.size == 0 {
            return Err(EngineError::InvalidArgument(format!(
                "buffer {} has size 0",
                desc.name
            )));
        }
        let info = vk::BufferCreateInfo::default()
            .size(desc.size)
            .usage(desc.usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: device valid; info complete.
        let raw = unsafe { ctx.device().create_buffer(&info, None) }.vk("vkCreateBuffer")?;
        // SAFETY: raw was just created.
        let requirements = unsafe { ctx.device().get_buffer_memory_requirements(raw) };
        ctx.set_name(raw, &desc.name);
        Ok((
            Self {
                shared: ctx.shared.clone(),
                raw,
                allocation: None,
                size: desc.size,
                usage: desc.usage,
                location: desc.location,
                category: desc.category,
                name: desc.name.clone(),
                state: Mutex::default(),
            },
            requirements,
        ))
    }

    /// Binds an unbound buffer to `memory` at `offset` (memory owned elsewhere).
    pub fn bind(&self, memory: vk::DeviceMemory, offset: u64) -> Result<()> {
        // SAFETY: the caller provides memory that satisfies the buffer's requirements.
        unsafe {
            self.shared
                .device
                .bind_buffer_memory(self.raw, memory, offset)
        }
        .vk("vkBindBufferMemory")
    }

    /// The accesses and layout the render graph last left this buffer in.
    pub fn tracked_state(&self) -> ResourceState {
        *self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Records the state the buffer is left in (done by the render graph after each frame).
    pub fn set_tracked_state(&self, state: ResourceState) {
        *self.state.lock().unwrap_or_else(|p| p.into_inner()) = state;
    }

    /// Creates a device-local buffer holding `data`, copied through a staging buffer (a transfer
    /// source as well, so that [`Buffer::read`] can read it back).
    pub fn with_data(
        ctx: &Context,
        name: &str,
        category: &'static str,
        usage: vk::BufferUsageFlags,
        data: &[u8],
    ) -> Result<Self> {
        let buffer = Self::new(
            ctx,
            &BufferDesc {
                name: name.to_string(),
                size: data.len().max(4) as u64,
                usage: usage
                    | vk::BufferUsageFlags::TRANSFER_DST
                    | vk::BufferUsageFlags::TRANSFER_SRC,
                location: MemoryLocation::GpuOnly,
                category,
            },
        )?;
        buffer.upload(ctx, data)?;
        Ok(buffer)
    }

    /// Copies `data` to the start of this buffer through a staging buffer, and waits.
    pub fn upload(&self, ctx: &Context, data: &[u8]) -> Result<()> {
        if data.is_empty() {
            return Ok(());
        }
        if data.len() as u64 > self.size {
            return Err(EngineError::InvalidArgument(format!(
                "uploading {} bytes into buffer {} of {} bytes",
                data.len(),
                self.name,
                self.size
            )));
        }
        let staging = Self::new(
            ctx,
            &BufferDesc {
                name: format!("{} (staging)", self.name),
                size: data.len() as u64,
                usage: vk::BufferUsageFlags::TRANSFER_SRC,
                location: MemoryLocation::CpuToGpu,
                category: "staging",
            },
        )?;
        staging.write(0, data)?;
        ctx.submit_and_wait(&format!("upload {}", self.name), |cmd| {
            let region = vk::BufferCopy::default().size(data.len() as u64);
            // SAFETY: both buffers are valid and large enough; cmd is recording.
            unsafe {
                ctx.device()
                    .cmd_copy_buffer(cmd, staging.raw, self.raw, &[region])
            };
        })
    }

    /// Writes `data` at `offset` into a host-visible buffer.
    pub fn write(&self, offset: u64, data: &[u8]) -> Result<()> {
        let end = offset
            .checked_add(data.len() as u64)
            .filter(|&end| end <= self.size)
            .ok_or_else(|| {
                EngineError::InvalidArgument(format!(
                    "writing {} bytes at {offset} overflows buffer {} ({} bytes)",
                    data.len(),
                    self.name,
                    self.size
                ))
            })?;
        let ptr = self
            .allocation
            .as_ref()
            .and_then(|a| a.mapped_ptr())
            .ok_or_else(|| self.not_mapped())?;
        // SAFETY: the mapping covers `size` bytes (checked above) and lives as long as the allocation;
        // callers synchronise with the GPU before writing (uploads wait, per-frame data is ring-buffered).
        unsafe {
            std::ptr::copy_nonoverlapping(
                data.as_ptr(),
                ptr.as_ptr().cast::<u8>().add(offset as usize),
                data.len(),
            )
        };
        debug_assert!(end <= self.size);
        Ok(())
    }

    /// The contents of a host-visible buffer.
    pub fn mapped(&self) -> Result<&[u8]> {
        self.allocation
            .as_ref()
            .and_then(|a| a.mapped_slice())
            .map(|s| &s[..self.size as usize])
            .ok_or_else(|| self.not_mapped())
    }

    fn not_mapped(&self) -> EngineError {
        EngineError::InvalidArgument(format!("buffer {} is not host-visible", self.name))
    }

    /// Copies the whole buffer to the CPU, and waits: a host-visible one (`CpuToGpu`, `GpuToCpu`)
    /// from its mapping, any other through a readback buffer, which needs `TRANSFER_SRC` in its
    /// usage. A GPU-only buffer is copied even where the driver maps it (lavapipe maps every
    /// allocation), so that reading one behaves as on a discrete GPU, where it is not mapped.
    pub fn read(&self, ctx: &Context) -> Result<Vec<u8>> {
        if matches!(
            self.location,
            MemoryLocation::CpuToGpu | MemoryLocation::GpuToCpu
        ) {
            return Ok(self.mapped()?.to_vec());
        }
        if !self.usage.contains(vk::BufferUsageFlags::TRANSFER_SRC) {
            return Err(EngineError::InvalidArgument(format!(
                "buffer {} is GPU-only and not a transfer source (TRANSFER_SRC): it cannot be read back",
                self.name
            )));
        }
        let readback = Self::new(
            ctx,
            &BufferDesc {
                name: format!("{} (readback)", self.name),
                size: self.size,
                usage: vk::BufferUsageFlags::TRANSFER_DST,
                location: MemoryLocation::GpuToCpu,
                category: "readback",
            },
        )?;
        ctx.submit_and_wait(&format!("read {}", self.name), |cmd| {
            let device = ctx.device();
            let before = [vk::MemoryBarrier2::default()
                .src_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
                .src_access_mask(vk::AccessFlags2::MEMORY_WRITE)
                .dst_stage_mask(vk::PipelineStageFlags2::COPY)
                .dst_access_mask(vk::AccessFlags2::TRANSFER_READ)];
            let after = [vk::MemoryBarrier2::default()
                .src_stage_mask(vk::PipelineStageFlags2::COPY)
                .src_access_mask(vk::AccessFlags2::TRANSFER_WRITE)
                .dst_stage_mask(vk::PipelineStageFlags2::HOST)
                .dst_access_mask(vk::AccessFlags2::HOST_READ)];
            let region = vk::BufferCopy::default().size(self.size);
            // SAFETY: cmd is recording; both buffers are valid.
            unsafe {
                device.cmd_pipeline_barrier2(
                    cmd,
                    &vk::DependencyInfo::default().memory_barriers(&before),
                );
                device.cmd_copy_buffer(cmd, self.raw, readback.raw, &[region]);
                device.cmd_pipeline_barrier2(
                    cmd,
                    &vk::DependencyInfo::default().memory_barriers(&after),
                );
            }
        })?;
        Ok(readback.mapped()?.to_vec())
    }

    /// The Vulkan handle.
    pub fn raw(&self) -> vk::Buffer {
        self.raw
    }

    /// Size in bytes.
    pub fn size(&self) -> u64 {
        self.size
    }

    /// Debug name.
    pub fn name(&self) -> &str {
        &self.name
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        // SAFETY: the owner guarantees the GPU no longer uses the buffer (frames are waited on).
        unsafe { self.shared.device.destroy_buffer(self.raw, None) };
        if let Some(allocation) = self.allocation.take() {
            free(&self.shared, self.category, allocation);
        }
    }
}
