//! The synchronization state a buffer or image is left in: what the next barrier on it must wait for.

use ash::vk;

/// The accumulated state of a resource: its layout and the accesses since the last barrier covering
/// them. This is what a later barrier must wait for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ResourceState {
    /// Current image layout (`UNDEFINED` for buffers and fresh images).
    pub layout: vk::ImageLayout,
    /// Stages that accessed it since the last barrier.
    pub stage: vk::PipelineStageFlags2,
    /// Accesses since the last barrier (writes matter for memory dependencies).
    pub access: vk::AccessFlags2,
}

impl Default for ResourceState {
    fn default() -> Self {
        Self {
            layout: vk::ImageLayout::UNDEFINED,
            stage: vk::PipelineStageFlags2::NONE,
            access: vk::AccessFlags2::NONE,
        }
    }
}
