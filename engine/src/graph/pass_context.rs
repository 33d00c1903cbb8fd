//! What a pass sees while recording: bind declared resources by the shader's reflected names and
//! dispatch by thread count.

use super::handle::{BufferHandle, Handle, ImageHandle, ResourceId};
use super::GraphError;
use crate::access::Access;
use crate::context::Context;
use crate::error::{EngineError, Result};
use crate::memory::{Buffer, Image};
use crate::shader::{
    ComputePipeline, DescriptorKind, ShaderLibrary, ShaderSource, SpecValue, Specialization,
};
use ash::vk;
use std::collections::HashMap;
use std::sync::Arc;

/// The physical resource behind a graph resource during execution.
#[derive(Clone)]
pub(crate) enum Physical {
    Image(Arc<Image>),
    Buffer(Arc<Buffer>),
}

/// The recording context handed to a pass's callback.
pub struct PassContext<'a> {
    pub(crate) ctx: &'a Context,
    pub(crate) cmd: vk::CommandBuffer,
    pub(crate) library: &'a ShaderLibrary,
    pub(crate) physical: &'a HashMap<ResourceId, Physical>,
    pub(crate) names: &'a [String],
    pub(crate) accesses: &'a [(ResourceId, u32, Access)],
    pub(crate) pass_name: &'a str,
    pub(crate) keep_alive: &'a mut Vec<Arc<ComputePipeline>>,
    pub(crate) history_valid: &'a HashMap<ResourceId, bool>,
    pub(crate) frame_index: u64,
}

impl<'a> PassContext<'a> {
    /// Starts a compute dispatch of `shader`: bind resources by name, set push constants and
    /// specialization constants, then dispatch.
    pub fn compute<'p>(&'p mut self, shader: &ShaderSource) -> Dispatch<'p, 'a> {
        Dispatch {
            pcx: self,
            shader: *shader,
            spec: Specialization::new(),
            images: Vec::new(),
            buffers: Vec::new(),
            push: Vec::new(),
        }
    }

    /// The command buffer, for commands the graph does not wrap. Barriers for declared resources
    /// are already recorded.
    pub fn command_buffer(&self) -> vk::CommandBuffer {
        self.cmd
    }

    /// Makes every compute shader write recorded so far visible to the compute shaders recorded
    /// after it: between the dispatches of one pass that reads what its previous dispatch wrote.
    pub fn compute_barrier(&self) {
        let stage = vk::PipelineStageFlags2::COMPUTE_SHADER;
        let barrier = vk::MemoryBarrier2::default()
            .src_stage_mask(stage)
            .src_access_mask(vk::AccessFlags2::SHADER_STORAGE_WRITE)
            .dst_stage_mask(stage)
            .dst_access_mask(
                vk::AccessFlags2::SHADER_STORAGE_READ | vk::AccessFlags2::SHADER_STORAGE_WRITE,
            );
        let barriers = [barrier];
        let info = vk::DependencyInfo::default().memory_barriers(&barriers);
        // SAFETY: cmd is recording.
        unsafe { self.ctx.device().cmd_pipeline_barrier2(self.cmd, &info) };
    }

    /// The Vulkan context.
    pub fn context(&self) -> &Context {
        self.ctx
    }

    /// The index of the frame being recorded (counts from 0 since the executor was created).
    pub fn frame_index(&self) -> u64 {
        self.frame_index
    }

    /// Whether a temporal `prev` handle holds last frame's history (false after a reset or resize,
    /// when it is cleared to zero).
    pub fn history_valid(&self, prev: ImageHandle) -> bool {
        self.history_valid.get(&prev.id).copied().unwrap_or(false)
    }

    fn declared<H: Handle>(&self, handle: H, binding: &str) -> Result<Access> {
        self.accesses
            .iter()
            .find(|&&(id, version, _)| id == handle.id() && version == handle.version())
            .map(|&(_, _, access)| access)
            .ok_or_else(|| {
                EngineError::Graph(GraphError::Undeclared {
                    pass: self.pass_name.to_string(),
                    resource: self.resource_name(handle.id()),
                    binding: binding.to_string(),
                })
            })
    }

    fn resource_name(&self, id: ResourceId) -> String {
        self.names.get(id.0 as usize).cloned().unwrap_or_default()
    }

    /// The physical image behind a declared handle.
    pub fn image(&self, handle: ImageHandle) -> Result<&Arc<Image>> {
        self.declared(handle, "image")?;
        match self.physical.get(&handle.id) {
            Some(Physical::Image(image)) => Ok(image),
            _ => Err(self.missing(handle.id)),
        }
    }

    /// The physical buffer behind a declared handle.
    pub fn buffer(&self, handle: BufferHandle) -> Result<&Arc<Buffer>> {
        self.declared(handle, "buffer")?;
        match self.physical.get(&handle.id) {
            Some(Physical::Buffer(buffer)) => Ok(buffer),
            _ => Err(self.missing(handle.id)),
        }
    }

    /// Writes `data` at the start of a buffer the pass declared with `Access::TransferWrite`, inline in
    /// the command buffer (in chunks of 64 KiB; the length must be a multiple of 4): per-frame
    /// constants need no staging buffer.
    pub fn update_buffer(&self, handle: BufferHandle, data: &[u8]) -> Result<()> {
        self.require_transfer_write(handle, "update_buffer")?;
        let buffer = self.buffer(handle)?;
        if data.is_empty() || data.len() % 4 != 0 || data.len() as u64 > buffer.size() {
            return Err(EngineError::InvalidArgument(format!(
                "pass {}: update_buffer takes a non-empty multiple of 4 bytes that fits {} ({} bytes), not {}",
                self.pass_name,
                buffer.name(),
                buffer.size(),
                data.len()
            )));
        }
        for (i, chunk) in data.chunks(65536).enumerate() {
            // SAFETY: cmd is recording; the buffer is alive for the frame and in transfer-write state;
            // the chunk lies within the buffer (checked above).
            unsafe {
                self.ctx.device().cmd_update_buffer(
                    self.cmd,
                    buffer.raw(),
                    (i * 65536) as u64,
                    chunk,
                )
            };
        }
        Ok(())
    }

    /// Fills a buffer the pass declared with `Access::TransferWrite` with a repeated 32-bit value.
    pub fn fill_buffer(&self, handle: BufferHandle, value: u32) -> Result<()> {
        self.require_transfer_write(handle, "fill_buffer")?;
        let buffer = self.buffer(handle)?;
        // SAFETY: cmd is recording; the buffer is alive for the frame and in transfer-write state.
        unsafe {
            self.ctx
                .device()
                .cmd_fill_buffer(self.cmd, buffer.raw(), 0, vk::WHOLE_SIZE, value)
        };
        Ok(())
    }

    /// Clears an image the pass declared with `Access::TransferWrite` to `color`.
    pub fn clear_image(&self, handle: ImageHandle, color: [f32; 4]) -> Result<()> {
        self.require_transfer_write(handle, "clear_image")?;
        let image = self.image(handle)?;
        let value = vk::ClearColorValue { float32: color };
        // SAFETY: cmd is recording; the image is alive for the frame and in transfer-dst layout.
        unsafe {
            self.ctx.device().cmd_clear_color_image(
                self.cmd,
                image.raw(),
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &value,
                &[crate::memory::color_range()],
            )
        };
        Ok(())
    }

    fn require_transfer_write<H: Handle>(&self, handle: H, what: &str) -> Result<()> {
        let access = self.declared(handle, what)?;
        if access == Access::TransferWrite {
            Ok(())
        } else {
            Err(EngineError::InvalidArgument(format!(
                "pass {}: {what} needs Access::TransferWrite on {}, not {access:?}",
                self.pass_name,
                self.resource_name(handle.id())
            )))
        }
    }

    fn missing(&self, id: ResourceId) -> EngineError {
        EngineError::InvalidArgument(format!(
            "pass {}: resource {} has no physical resource",
            self.pass_name,
            self.resource_name(id)
        ))
    }
}

/// How many workgroups a dispatch runs.
enum Work {
    /// Enough to cover this many invocations.
    Threads([u32; 3]),
    /// Exactly these.
    Groups([u32; 3]),
    /// As many as the GPU reads from the buffer at this byte offset.
    Indirect(BufferHandle, u64),
}

/// What a dispatch records, resolved from its [`Work`].
enum Launch {
    /// `vkCmdDispatch` of these workgroups (none when any is 0).
    Groups([u32; 3]),
    /// `vkCmdDispatchIndirect` from this buffer at this byte offset.
    Indirect(vk::Buffer, u64),
}

/// A compute dispatch being set up; see [`PassContext::compute`].
pub struct Dispatch<'p, 'a> {
    pcx: &'p mut PassContext<'a>,
    shader: ShaderSource,
    spec: Specialization,
    images: Vec<(String, ImageHandle)>,
    buffers: Vec<(String, BufferHandle)>,
    push: Vec<u8>,
}

impl Dispatch<'_, '_> {
    /// Binds an image to the shader binding `name`.
    pub fn image(mut self, name: &str, handle: ImageHandle) -> Self {
        self.images.push((name.to_string(), handle));
        self
    }

    /// Binds a buffer to the shader binding `name` (variable or block name).
    pub fn buffer(mut self, name: &str, handle: BufferHandle) -> Self {
        self.buffers.push((name.to_string(), handle));
        self
    }

    /// Sets push constants (their size must equal the shader's push-constant block).
    pub fn push<T: bytemuck::Pod>(mut self, data: &T) -> Self {
        self.push = bytemuck::bytes_of(data).to_vec();
        self
    }

    /// Sets a specialization constant by name.
    pub fn specialize(mut self, name: &str, value: impl Into<SpecValue>) -> Self {
        self.spec = self.spec.set(name, value);
        self
    }

    /// Sets several specialization constants.
    pub fn specialization(mut self, spec: &Specialization) -> Self {
        for (name, value) in spec.values() {
            self.spec = self.spec.set(name, *value);
        }
        self
    }

    /// Dispatches enough workgroups to cover `threads` invocations (the workgroup size comes from
    /// the shader); the shader must bounds-check.
    pub fn dispatch_threads(self, threads: [u32; 3]) -> Result<()> {
        self.record(Work::Threads(threads))
    }

    /// Dispatches exactly `groups` workgroups.
    pub fn dispatch_groups(self, groups: [u32; 3]) -> Result<()> {
        self.record(Work::Groups(groups))
    }

    /// Dispatches the workgroup counts that the GPU finds in `args` at byte `offset` (a
    /// `VkDispatchIndirectCommand`: three u32, `offset` a multiple of 4, within the buffer), which
    /// the pass must have declared with [`Access::IndirectCommandRead`], so that the graph orders
    /// the dispatch after the pass that wrote the counts.
    pub fn dispatch_indirect(self, args: BufferHandle, offset: u64) -> Result<()> {
        self.record(Work::Indirect(args, offset))
    }

    fn error(&self, message: String) -> EngineError {
        EngineError::Shader {
            shader: self.shader.name.to_string(),
            message: format!("in pass {}: {message}", self.pcx.pass_name),
        }
    }

    /// The launch of indirect arguments at byte `offset` of `args`, checked: declared with
    /// [`Access::IndirectCommandRead`], the command within the buffer and aligned.
    fn indirect(&self, args: BufferHandle, offset: u64) -> Result<Launch> {
        let access = self.pcx.declared(args, "indirect arguments")?;
        if access != Access::IndirectCommandRead {
            return Err(self.error(format!(
                "indirect arguments {} need Access::IndirectCommandRead, not {access:?}",
                self.pcx.resource_name(args.id())
            )));
        }
        let buffer = self.pcx.buffer(args)?;
        if offset % 4 != 0 || offset + 12 > buffer.size() {
            return Err(self.error(format!(
                "indirect arguments at byte {offset} do not fit {} ({} bytes) or are not 4-byte aligned",
                buffer.name(),
                buffer.size()
            )));
        }
        Ok(Launch::Indirect(buffer.raw(), offset))
    }

    fn record(self, work: Work) -> Result<()> {
        let pipeline = self.pcx.library.pipeline(&self.shader, &self.spec)?;
        let reflection = pipeline.reflection.clone();
        let mut image_infos: Vec<(u32, vk::DescriptorType, vk::DescriptorImageInfo)> = Vec::new();
        let mut buffer_infos: Vec<(u32, vk::DescriptorType, vk::DescriptorBufferInfo)> = Vec::new();
        let mut bound: Vec<&str> = Vec::new();
        for (name, handle) in &self.images {
            let binding = reflection.binding(name).ok_or_else(|| {
                self.error(format!(
                    "has no binding named {name:?}; it has {:?}",
                    reflection.binding_names()
                ))
            })?;
            let access = self.pcx.declared(*handle, name)?;
            let (ty, layout) = match binding.kind {
                DescriptorKind::StorageImage => {
                    if !matches!(
                        access,
                        Access::ComputeRead | Access::ComputeWrite | Access::ComputeReadWrite
                    ) {
                        return Err(self.error(format!("storage image {name} needs a Compute read/write access, not {access:?}")));
                    }
                    if !binding.read_only && !access.info().writes {
                        return Err(self.error(format!("{name} is declared read-only by the pass but the shader may write it: mark it `readonly` in GLSL")));
                    }
                    (vk::DescriptorType::STORAGE_IMAGE, vk::ImageLayout::GENERAL)
                }
                DescriptorKind::SampledImage => {
                    if access != Access::ComputeSampled {
                        return Err(self.error(format!(
                            "sampler {name} needs Access::ComputeSampled, not {access:?}"
                        )));
                    }
                    (
                        vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                        vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                    )
                }
                _ => {
                    return Err(self.error(format!(
                        "{name} is a buffer binding; bind it with .buffer()"
                    )))
                }
            };
            let image = self.pcx.image(*handle)?;
            image_infos.push((
                binding.binding,
                ty,
                vk::DescriptorImageInfo::default()
                    .image_view(image.view())
                    .image_layout(layout),
            ));
            bound.push(&binding.name);
        }
        for (name, handle) in &self.buffers {
            let binding = reflection.binding(name).ok_or_else(|| {
                self.error(format!(
                    "has no binding named {name:?}; it has {:?}",
                    reflection.binding_names()
                ))
            })?;
            let access = self.pcx.declared(*handle, name)?;
            let ty = match binding.kind {
                DescriptorKind::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
                DescriptorKind::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
                _ => {
                    return Err(
                        self.error(format!("{name} is an image binding; bind it with .image()"))
                    )
                }
            };
            if !matches!(
                access,
                Access::ComputeRead | Access::ComputeWrite | Access::ComputeReadWrite
            ) {
                return Err(self.error(format!(
                    "buffer {name} needs a Compute access, not {access:?}"
                )));
            }
            if ty == vk::DescriptorType::STORAGE_BUFFER
                && !binding.read_only
                && !access.info().writes
            {
                return Err(self.error(format!("{name} is declared read-only by the pass but the shader may write it: mark it `readonly` in GLSL")));
            }
            let buffer = self.pcx.buffer(*handle)?;
            buffer_infos.push((
                binding.binding,
                ty,
                vk::DescriptorBufferInfo::default()
                    .buffer(buffer.raw())
                    .range(vk::WHOLE_SIZE),
            ));
            bound.push(&binding.name);
        }
        if let Some(missing) = reflection
            .bindings
            .iter()
            .find(|b| !bound.contains(&b.name.as_str()))
        {
            return Err(self.error(format!("binding {:?} was not bound", missing.name)));
        }
        if self.push.len() as u32 != reflection.push_constant_size {
            return Err(self.error(format!(
                "push constants are {} bytes but the shader expects {}",
                self.push.len(),
                reflection.push_constant_size
            )));
        }
        let wg = pipeline.workgroup_size;
        let launch = match work {
            Work::Threads(threads) => Launch::Groups([
                threads[0].div_ceil(wg[0]),
                threads[1].div_ceil(wg[1]),
                threads[2].div_ceil(wg[2]),
            ]),
            Work::Groups(groups) => Launch::Groups(groups),
            Work::Indirect(args, offset) => self.indirect(args, offset)?,
        };
        let device = self.pcx.ctx.device();
        let cmd = self.pcx.cmd;
        let writes: Vec<vk::WriteDescriptorSet> = image_infos
            .iter()
            .map(|(binding, ty, info)| {
                vk::WriteDescriptorSet::default()
                    .dst_binding(*binding)
                    .descriptor_type(*ty)
                    .image_info(std::slice::from_ref(info))
            })
            .chain(buffer_infos.iter().map(|(binding, ty, info)| {
                vk::WriteDescriptorSet::default()
                    .dst_binding(*binding)
                    .descriptor_type(*ty)
                    .buffer_info(std::slice::from_ref(info))
            }))
            .collect();
        // SAFETY: cmd is recording; the pipeline, views and buffers (the indirect arguments too,
        // checked above) are kept alive until the frame completes (pipelines via keep_alive,
        // resources via the executor's frame slot).
        unsafe {
            device.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline.pipeline);
            if !writes.is_empty() {
                self.pcx.ctx.shared.push_descriptor.cmd_push_descriptor_set(
                    cmd,
                    vk::PipelineBindPoint::COMPUTE,
                    pipeline.layout,
                    0,
                    &writes,
                );
            }
            if !self.push.is_empty() {
                device.cmd_push_constants(
                    cmd,
                    pipeline.layout,
                    vk::ShaderStageFlags::COMPUTE,
                    0,
                    &self.push,
                );
            }
            match launch {
                Launch::Groups(groups) if groups.iter().all(|&g| g > 0) => {
                    device.cmd_dispatch(cmd, groups[0], groups[1], groups[2]);
                }
                Launch::Groups(_) => {}
                Launch::Indirect(buffer, offset) => {
                    device.cmd_dispatch_indirect(cmd, buffer, offset);
                }
            }
        }
        self.pcx.keep_alive.push(pipeline);
        Ok(())
    }
}
