//! The compiled graph as plain data: order, culled passes, barriers, lifetimes and aliasing.

use super::handle::ResourceId;
use super::render_graph::{ResourceDesc, ResourceKind};
use crate::access::Access;
use crate::memory::ResourceState;
use ash::vk;

/// Where a barrier's source scope comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BarrierSrc {
    /// The resource's (or, for transients, its memory slot's) state when the frame starts, known only
    /// at execution: last frame's accesses, or an import's tracked state.
    FrameStart,
    /// Accesses earlier in this frame.
    Earlier {
        /// Stages to wait for.
        stage: vk::PipelineStageFlags2,
        /// Accesses to make available.
        access: vk::AccessFlags2,
    },
}

/// One barrier before a pass (synchronization2: execution and memory dependency, layout transition).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Barrier {
    /// The resource it guards.
    pub resource: ResourceId,
    /// What must finish first.
    pub src: BarrierSrc,
    /// Stages that wait.
    pub dst_stage: vk::PipelineStageFlags2,
    /// Accesses that must see the source's writes.
    pub dst_access: vk::AccessFlags2,
    /// The layout before (`None`: the layout at frame start; `UNDEFINED`: contents discarded).
    pub old_layout: Option<vk::ImageLayout>,
    /// The layout after.
    pub new_layout: vk::ImageLayout,
}

/// A pass that survived culling, in execution order.
#[derive(Clone, Debug)]
pub struct PlannedPass {
    /// The pass's name.
    pub name: String,
    /// Its index in declaration order.
    pub decl_index: usize,
    /// Barriers recorded before it.
    pub barriers: Vec<Barrier>,
    /// Everything it reads and writes: (resource, version, access).
    pub accesses: Vec<(ResourceId, u32, Access)>,
}

/// A resource of the compiled graph.
#[derive(Clone, Debug)]
pub struct PlannedResource {
    /// Debug name.
    pub name: String,
    /// Transient, imported or temporal.
    pub kind: ResourceKind,
    /// Size and format.
    pub desc: ResourceDesc,
    /// Union of the usage flags its accesses need (images).
    pub image_usage: vk::ImageUsageFlags,
    /// Union of the usage flags its accesses need (buffers).
    pub buffer_usage: vk::BufferUsageFlags,
    /// First and last position (in the kept pass order) that use it, when used at all.
    pub lifetime: Option<(usize, usize)>,
    /// The memory slot of a used transient.
    pub slot: Option<usize>,
}

/// Memory shared by transients whose lifetimes do not overlap.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AliasSlot {
    /// Whether it holds images (true) or buffers.
    pub images: bool,
    /// The largest member's data size, an estimate of the memory it needs.
    pub size_estimate: u64,
    /// Its transients, in order of first use.
    pub members: Vec<ResourceId>,
}

/// The plain-data result of compiling a graph.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Every declared resource, indexed by [`ResourceId`].
    pub resources: Vec<PlannedResource>,
    /// Kept passes in execution order.
    pub passes: Vec<PlannedPass>,
    /// Names of passes removed because nobody reads their outputs.
    pub culled: Vec<String>,
    /// Memory slots of transients.
    pub slots: Vec<AliasSlot>,
    /// State at frame end of each used imported or temporal resource.
    pub final_states: Vec<(ResourceId, ResourceState)>,
    /// State at frame end of each memory slot.
    pub slot_final_states: Vec<ResourceState>,
}

impl Plan {
    /// The resource named `name`.
    pub fn resource_id(&self, name: &str) -> Option<ResourceId> {
        self.resources
            .iter()
            .position(|r| r.name == name)
            .map(|i| ResourceId(i as u32))
    }

    /// The kept pass named `name`.
    pub fn pass(&self, name: &str) -> Option<&PlannedPass> {
        self.passes.iter().find(|p| p.name == name)
    }

    /// Names of kept passes in execution order.
    pub fn order(&self) -> Vec<&str> {
        self.passes.iter().map(|p| p.name.as_str()).collect()
    }

    /// Bytes of transient memory after aliasing (sum of slot estimates) and without it.
    pub fn transient_bytes(&self) -> (u64, u64) {
        let aliased = self.slots.iter().map(|s| s.size_estimate).sum();
        let unaliased = self
            .resources
            .iter()
            .filter(|r| r.slot.is_some())
            .map(|r| r.desc.byte_size())
            .sum();
        (aliased, unaliased)
    }
}
