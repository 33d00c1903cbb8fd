//! One frame slot of the frames in flight: command buffer, timestamp queries, and what the frame
//! must keep alive until the GPU finishes it.

use super::pass_context::Physical;
use crate::context::Context;
use crate::error::{Result, VkResultExt};
use crate::memory::Buffer;
use crate::shader::ComputePipeline;
use ash::vk;
use std::sync::Arc;

/// A pending readback: which readback, its buffer, and the image format (None for buffers).
pub(crate) struct PendingReadback {
    pub index: usize,
    pub buffer: Arc<Buffer>,
    pub image: Option<crate::memory::ImageDesc>,
}

pub(crate) struct FrameSlot {
    pub pool: vk::CommandPool,
    pub cmd: vk::CommandBuffer,
    pub queries: vk::QueryPool,
    pub query_capacity: u32,
    /// The timeline value that signals this slot's completion (0: never submitted).
    pub value: u64,
    /// Whether its results were collected after completion.
    pub collected: bool,
    pub pass_names: Vec<String>,
    pub pipelines: Vec<Arc<ComputePipeline>>,
    pub resources: Vec<Physical>,
    pub readbacks: Vec<PendingReadback>,
}

impl FrameSlot {
    pub fn new(ctx: &Context, index: usize) -> Result<Self> {
        let device = ctx.device();
        let info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.queue_family())
            .flags(vk::CommandPoolCreateFlags::TRANSIENT);
        // SAFETY: device valid.
        let pool = unsafe { device.create_command_pool(&info, None) }.vk("vkCreateCommandPool")?;
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(1);
        // SAFETY: pool valid.
        let cmd = match unsafe { device.allocate_command_buffers(&alloc) } {
            Ok(c) => c[0],
            Err(e) => {
                // SAFETY: pool unused.
                unsafe { device.destroy_command_pool(pool, None) };
                return Err(crate::error::from_vk("vkAllocateCommandBuffers", e));
            }
        };
        ctx.set_name(cmd, &format!("frame slot {index}"));
        Ok(Self {
            pool,
            cmd,
            queries: vk::QueryPool::null(),
            query_capacity: 0,
            value: 0,
            collected: true,
            pass_names: Vec::new(),
            pipelines: Vec::new(),
            resources: Vec::new(),
            readbacks: Vec::new(),
        })
    }

    /// Makes room for `count` timestamps.
    pub fn ensure_queries(&mut self, ctx: &Context, count: u32) -> Result<()> {
        if count <= self.query_capacity {
            return Ok(());
        }
        let device = ctx.device();
        if self.queries != vk::QueryPool::null() {
            // SAFETY: the slot's previous frame completed before reuse.
            unsafe { device.destroy_query_pool(self.queries, None) };
        }
        let capacity = count.next_power_of_two().max(16);
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::TIMESTAMP)
            .query_count(capacity);
        // SAFETY: device valid.
        self.queries = unsafe { device.create_query_pool(&info, None) }.vk("vkCreateQueryPool")?;
        self.query_capacity = capacity;
        Ok(())
    }

    /// Releases what the completed frame kept alive.
    pub fn release(&mut self) {
        self.pipelines.clear();
        self.resources.clear();
    }

    pub fn destroy(&mut self, ctx: &Context) {
        self.release();
        self.readbacks.clear();
        // SAFETY: the executor waited for every frame before destroying slots.
        unsafe {
            if self.queries != vk::QueryPool::null() {
                ctx.device().destroy_query_pool(self.queries, None);
            }
            ctx.device().destroy_command_pool(self.pool, None);
        }
    }
}
