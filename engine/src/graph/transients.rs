//! Physical transients, kept across frames while the graph's shape stays the same. Members of one
//! alias slot are bound into one shared memory block.

use super::handle::ResourceId;
use super::pass_context::Physical;
use super::plan::Plan;
use super::render_graph::{ResourceDesc, ResourceKind};
use crate::context::Context;
use crate::error::Result;
use crate::memory::ResourceState;
use crate::memory::{Buffer, BufferDesc, Image, MemoryBlock, MemoryLocation};
use ash::vk;
use std::collections::HashMap;
use std::sync::Arc;

/// What identifies the pool's contents: per used transient, its description, usage and slot.
type Signature = Vec<(
    ResourceDesc,
    vk::ImageUsageFlags,
    vk::BufferUsageFlags,
    usize,
)>;

#[derive(Default)]
pub(crate) struct TransientPool {
    signature: Signature,
    /// Physical resources in signature order. Declared before `blocks`: dropped first.
    resources: Vec<Physical>,
    blocks: Vec<MemoryBlock>,
    /// Each slot's state at the end of the last frame (the source of its first barrier).
    pub slot_states: Vec<ResourceState>,
}

fn signature(plan: &Plan) -> (Signature, Vec<ResourceId>) {
    let mut sig = Vec::new();
    let mut ids = Vec::new();
    for (i, r) in plan.resources.iter().enumerate() {
        if let (ResourceKind::Transient, Some(slot)) = (&r.kind, r.slot) {
            sig.push((r.desc, r.image_usage, r.buffer_usage, slot));
            ids.push(ResourceId(i as u32));
        }
    }
    (sig, ids)
}

impl TransientPool {
    /// Whether the pool already matches `plan`'s transients.
    pub fn matches(&self, plan: &Plan) -> bool {
        signature(plan).0 == self.signature
    }

    /// Recreates the pool for `plan`. The caller has waited for every frame using the old pool.
    /// Fails, holding nothing, when the transients do not fit in the memory budget.
    pub fn rebuild(&mut self, ctx: &Context, plan: &Plan) -> Result<()> {
        self.signature.clear();
        self.resources.clear();
        self.blocks.clear();
        let (sig, ids) = signature(plan);
        let mut resources: Vec<Option<Physical>> = Vec::with_capacity(sig.len());
        let mut requirements: Vec<vk::MemoryRequirements> = Vec::with_capacity(sig.len());
        for (&(desc, image_usage, buffer_usage, _), id) in sig.iter().zip(&ids) {
            let name = &plan.resources[id.0 as usize].name;
            match desc {
                ResourceDesc::Image(d) => {
                    let image = Image::unbound(ctx, name, d, image_usage)?;
                    requirements.push(image.memory_requirements());
                    resources.push(Some(Physical::Image(Arc::new(image))));
                }
                ResourceDesc::Buffer(size) => {
                    let (buffer, req) = Buffer::unbound(
                        ctx,
                        &BufferDesc {
                            name: name.clone(),
                            size,
                            usage: buffer_usage,
                            location: MemoryLocation::GpuOnly,
                            category: "graph.transient",
                        },
                    )?;
                    requirements.push(req);
                    resources.push(Some(Physical::Buffer(Arc::new(buffer))));
                }
            }
        }
        let mut blocks = Vec::new();
        for (s, slot) in plan.slots.iter().enumerate() {
            let members: Vec<usize> = (0..sig.len()).filter(|&i| sig[i].3 == s).collect();
            let mut req = vk::MemoryRequirements {
                size: 0,
                alignment: 1,
                memory_type_bits: u32::MAX,
            };
            for &m in &members {
                req.size = req.size.max(requirements[m].size);
                req.alignment = req.alignment.max(requirements[m].alignment);
                req.memory_type_bits &= requirements[m].memory_type_bits;
            }
            // Members with incompatible memory types get blocks of their own.
            if req.memory_type_bits == 0 {
                blocks.extend(
                    members
                        .iter()
                        .map(|&m| (s, slot.images, vec![m], requirements[m])),
                );
            } else {
                blocks.push((s, slot.images, members, req));
            }
        }
        let total: u64 = blocks.iter().map(|b| b.3.size).sum();
        let largest = sig
            .iter()
            .zip(&ids)
            .zip(&requirements)
            .max_by_key(|(_, req)| req.size)
            .map(|((_, id), _)| plan.resources[id.0 as usize].name.as_str())
            .unwrap_or("none");
        ctx.shared.budget.check(
            &format!(
                "the frame's {} transient images and buffers (aliased into {} blocks; the \
                 largest: {largest})",
                sig.len(),
                blocks.len()
            ),
            total,
            ctx.shared.memory.total_bytes(),
            false,
        )?;
        for (s, images, group, group_req) in blocks {
            let block = MemoryBlock::new(
                ctx,
                &format!("transient slot {s}"),
                "graph.transient",
                group_req,
                !images,
            )?;
            let (memory, offset) = block.memory();
            for &m in &group {
                match resources[m].as_mut() {
                    Some(Physical::Image(image)) => {
                        let image = Arc::get_mut(image).expect("new image is not shared");
                        image.bind(ctx, memory, offset)?;
                    }
                    Some(Physical::Buffer(buffer)) => buffer.bind(memory, offset)?,
                    None => {}
                }
            }
            self.blocks.push(block);
        }
        self.resources = resources.into_iter().flatten().collect();
        self.signature = sig;
        self.slot_states = vec![ResourceState::default(); plan.slots.len()];
        Ok(())
    }

    /// The physical resource of each used transient of `plan` (which the pool matches).
    pub fn physical(&self, plan: &Plan) -> HashMap<ResourceId, Physical> {
        let (_, ids) = signature(plan);
        ids.into_iter()
            .zip(self.resources.iter().cloned())
            .collect()
    }
}
