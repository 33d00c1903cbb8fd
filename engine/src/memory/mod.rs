//! GPU memory: buffers and images allocated through gpu-allocator, staging uploads, readback,
//! and a report of what is allocated by category.

mod block;
mod buffer;
mod format;
mod image;
mod resource_state;

pub use crate::context::memory_report::{MemoryReport, MemoryTracker};
pub use block::MemoryBlock;
pub use buffer::{Buffer, BufferDesc};
pub use format::{texels_to_rgba, FormatInfo};
pub use image::{color_range, Image, ImageDesc};
pub use resource_state::ResourceState;

pub use gpu_allocator::MemoryLocation;

use crate::context::Context;
use crate::error::{EngineError, Result};
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};

/// Allocates memory for `requirements` from the context's allocator, recording it under `category`.
pub(crate) fn allocate(
    ctx: &Context,
    name: &str,
    category: &'static str,
    requirements: ash::vk::MemoryRequirements,
    location: MemoryLocation,
    linear: bool,
) -> Result<Allocation> {
    ctx.shared.budget.check(
        name,
        requirements.size,
        ctx.shared.memory.total_bytes(),
        true,
    )?;
    let mut allocator = ctx
        .shared
        .allocator
        .lock()
        .unwrap_or_else(|poison| poison.into_inner());
    let allocation = allocator
        .allocate(&AllocationCreateDesc {
            name,
            requirements,
            location,
            linear,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        })
        .map_err(|e| match e {
            gpu_allocator::AllocationError::OutOfMemory => EngineError::OutOfDeviceMemory {
                what: name.to_string(),
                bytes: requirements.size,
            },
            other => EngineError::InvalidArgument(format!("allocating {name}: {other}")),
        })?;
    ctx.shared.memory.record(category, allocation.size());
    Ok(allocation)
}

/// Returns an allocation to the allocator and the category tracker.
pub(crate) fn free(
    ctx_shared: &crate::context::Shared,
    category: &'static str,
    allocation: Allocation,
) {
    ctx_shared.memory.release(category, allocation.size());
    let mut allocator = ctx_shared
        .allocator
        .lock()
        .unwrap_or_else(|poison| poison.into_inner());
    if let Err(e) = allocator.free(allocation) {
        tracing::error!("freeing GPU memory failed: {e}");
    }
}

impl Context {
    /// What is allocated now, by category, with the allocator's totals.
    pub fn memory_report(&self) -> MemoryReport {
        let allocator = self
            .shared
            .allocator
            .lock()
            .unwrap_or_else(|poison| poison.into_inner());
        let report = allocator.generate_report();
        self.shared
            .memory
            .report(report.total_allocated_bytes, report.total_capacity_bytes)
    }
}
