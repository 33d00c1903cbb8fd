//! Access types: how a pass uses a resource. Everything derived (image layouts, pipeline stages,
//! memory access masks, usage flags at allocation) comes from here.

use ash::vk;

/// How a pass touches a resource.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Access {
    /// Not yet used: contents undefined.
    None,
    /// Compute shader reads it as a storage image or storage/uniform buffer.
    ComputeRead,
    /// Compute shader writes it (storage image or buffer).
    ComputeWrite,
    /// Compute shader reads and writes it.
    ComputeReadWrite,
    /// Compute shader samples it through a sampler (`sampler2D`).
    ComputeSampled,
    /// Read by `vkCmdDispatchIndirect` as its workgroup counts (a buffer; the indirect-command
    /// stage, before the compute shader runs).
    IndirectCommandRead,
    /// Source of a copy.
    TransferRead,
    /// Destination of a copy or clear.
    TransferWrite,
    /// Fragment shader samples it (e.g. the UI pass drawing the image).
    FragmentSampled,
    /// Written as a colour attachment.
    ColorAttachmentWrite,
    /// Handed to the presentation engine.
    Present,
}

/// The Vulkan facts behind an [`Access`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccessInfo {
    /// Pipeline stages that perform the access.
    pub stage: vk::PipelineStageFlags2,
    /// Memory access mask.
    pub access: vk::AccessFlags2,
    /// Image layout required during the access.
    pub layout: vk::ImageLayout,
    /// Whether the access writes.
    pub writes: bool,
    /// Whether the access reads.
    pub reads: bool,
}

impl Access {
    /// The stages, access mask and layout of this access.
    pub fn info(self) -> AccessInfo {
        use vk::AccessFlags2 as A;
        use vk::ImageLayout as L;
        use vk::PipelineStageFlags2 as S;
        let (stage, access, layout, reads, writes) = match self {
            Access::None => (S::NONE, A::NONE, L::UNDEFINED, false, false),
            Access::ComputeRead => (
                S::COMPUTE_SHADER,
                A::SHADER_STORAGE_READ | A::UNIFORM_READ,
                L::GENERAL,
                true,
                false,
            ),
            Access::ComputeWrite => (
                S::COMPUTE_SHADER,
                A::SHADER_STORAGE_WRITE,
                L::GENERAL,
                false,
                true,
            ),
            Access::ComputeReadWrite => (
                S::COMPUTE_SHADER,
                A::SHADER_STORAGE_READ | A::SHADER_STORAGE_WRITE,
                L::GENERAL,
                true,
                true,
            ),
            Access::ComputeSampled => (
                S::COMPUTE_SHADER,
                A::SHADER_SAMPLED_READ,
                L::SHADER_READ_ONLY_OPTIMAL,
                true,
                false,
            ),
            // Buffers only, which have no layout: GENERAL, as for the compute accesses.
            Access::IndirectCommandRead => (
                S::DRAW_INDIRECT,
                A::INDIRECT_COMMAND_READ,
                L::GENERAL,
                true,
                false,
            ),
            Access::TransferRead => (
                S::COPY,
                A::TRANSFER_READ,
                L::TRANSFER_SRC_OPTIMAL,
                true,
                false,
            ),
            Access::TransferWrite => (
                S::COPY | S::CLEAR,
                A::TRANSFER_WRITE,
                L::TRANSFER_DST_OPTIMAL,
                false,
                true,
            ),
            Access::FragmentSampled => (
                S::FRAGMENT_SHADER,
                A::SHADER_SAMPLED_READ,
                L::SHADER_READ_ONLY_OPTIMAL,
                true,
                false,
            ),
            Access::ColorAttachmentWrite => (
                S::COLOR_ATTACHMENT_OUTPUT,
                A::COLOR_ATTACHMENT_WRITE | A::COLOR_ATTACHMENT_READ,
                L::COLOR_ATTACHMENT_OPTIMAL,
                true,
                true,
            ),
            Access::Present => (S::NONE, A::NONE, L::PRESENT_SRC_KHR, true, false),
        };
        AccessInfo {
            stage,
            access,
            layout,
            writes,
            reads,
        }
    }

    /// Image usage flags this access needs.
    pub fn image_usage(self) -> vk::ImageUsageFlags {
        use vk::ImageUsageFlags as U;
        match self {
            Access::None | Access::Present | Access::IndirectCommandRead => U::empty(),
            Access::ComputeRead | Access::ComputeWrite | Access::ComputeReadWrite => U::STORAGE,
            Access::ComputeSampled | Access::FragmentSampled => U::SAMPLED,
            Access::TransferRead => U::TRANSFER_SRC,
            Access::TransferWrite => U::TRANSFER_DST,
            Access::ColorAttachmentWrite => U::COLOR_ATTACHMENT,
        }
    }

    /// Buffer usage flags this access needs.
    pub fn buffer_usage(self) -> vk::BufferUsageFlags {
        use vk::BufferUsageFlags as U;
        match self {
            Access::ComputeRead | Access::ComputeWrite | Access::ComputeReadWrite => {
                U::STORAGE_BUFFER
            }
            Access::IndirectCommandRead => U::INDIRECT_BUFFER,
            Access::TransferRead => U::TRANSFER_SRC,
            Access::TransferWrite => U::TRANSFER_DST,
            _ => U::empty(),
        }
    }
}
