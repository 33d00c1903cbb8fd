//! A block of device memory shared by several resources (the render graph's aliased transients).

use super::{allocate, free, MemoryLocation};
use crate::context::{Context, Shared};
use crate::error::Result;
use ash::vk;
use gpu_allocator::vulkan::Allocation;
use std::sync::Arc;

/// Device-local memory that resources are bound into. Drop the resources first.
pub struct MemoryBlock {
    shared: Arc<Shared>,
    allocation: Option<Allocation>,
    category: &'static str,
}

impl MemoryBlock {
    /// Allocates memory satisfying `requirements`.
    pub fn new(
        ctx: &Context,
        name: &str,
        category: &'static str,
        requirements: vk::MemoryRequirements,
        linear: bool,
    ) -> Result<Self> {
        let allocation = allocate(
            ctx,
            name,
            category,
            requirements,
            MemoryLocation::GpuOnly,
            linear,
        )?;
        Ok(Self {
            shared: ctx.shared.clone(),
            allocation: Some(allocation),
            category,
        })
    }

    /// The memory object and the offset of this block in it.
    pub fn memory(&self) -> (vk::DeviceMemory, u64) {
        self.allocation
            .as_ref()
            .map_or((vk::DeviceMemory::null(), 0), |a| {
                // SAFETY: the allocation's memory stays valid while the block lives.
                (unsafe { a.memory() }, a.offset())
            })
    }
}

impl Drop for MemoryBlock {
    fn drop(&mut self) {
        if let Some(allocation) = self.allocation.take() {
            free(&self.shared, self.category, allocation);
        }
    }
}
