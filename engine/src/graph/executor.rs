//! Execute: record a compiled graph into a frame slot's command buffer, resolve barriers against
//! tracked state, time each pass, submit with a timeline semaphore, and return readbacks.

use super::frame_slot::{FrameSlot, PendingReadback};
use super::handle::ResourceId;
use super::pass_context::{PassContext, Physical};
use super::plan::{Barrier, BarrierSrc, Plan};
use super::render_graph::{External, PassWork, ResourceDesc, ResourceKind};
use super::temporal::TemporalStore;
use super::transients::TransientPool;
use super::{CompiledGraph, GraphError, ReadbackId};
use crate::access::Access;
use crate::capture::ImageData;
use crate::context::Context;
use crate::error::{EngineError, Result, VkResultExt};
use crate::memory::ResourceState;
use crate::memory::{
    color_range, texels_to_rgba, Buffer, BufferDesc, Image, ImageDesc, MemoryLocation,
};
use crate::shader::ShaderLibrary;
use ash::vk;
use std::collections::HashMap;
use std::sync::Arc;

/// The `prev` and `cur` resources of one temporal key in a plan, and its description.
type TemporalIds = (Option<ResourceId>, Option<ResourceId>, ImageDesc);

/// Which `prev` handles hold history this frame, and the history images to clear first.
type TemporalBinding = (HashMap<ResourceId, bool>, Vec<Arc<Image>>);

/// Identifies a submitted frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FrameId(u64);

/// GPU time of one pass.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTiming {
    /// The pass's name.
    pub name: String,
    /// Milliseconds between the timestamps around the pass.
    pub ms: f64,
    /// Milliseconds from the timestamp before the frame's first pass to the one before this pass:
    /// with `ms`, where the pass lies in the frame, gaps between passes (their barriers) included.
    pub start_ms: f64,
}

/// Semaphores a submission waits on and signals (for presenting to a window).
#[derive(Clone, Default)]
pub struct SubmitOptions {
    /// Binary semaphores to wait on, with the stages that wait.
    pub wait: Vec<(vk::Semaphore, vk::PipelineStageFlags2)>,
    /// Binary semaphores to signal when the frame completes.
    pub signal: Vec<vk::Semaphore>,
}

/// What a completed frame returns.
#[derive(Default)]
pub struct FrameOutputs {
    readbacks: HashMap<usize, (Vec<u8>, Option<ImageDesc>)>,
    /// GPU time per pass.
    pub timings: Vec<PassTiming>,
}

impl FrameOutputs {
    /// A read-back image as linear RGBA.
    pub fn image(&self, id: ReadbackId) -> Result<ImageData> {
        match self.readbacks.get(&id.0) {
            Some((bytes, Some(desc))) => {
                let pixels = texels_to_rgba(desc.format, bytes).ok_or_else(|| {
                    EngineError::InvalidArgument(format!("cannot convert {:?} texels", desc.format))
                })?;
                Ok(ImageData {
                    width: desc.width,
                    height: desc.height,
                    pixels,
                })
            }
            _ => Err(GraphError::NoSuchReadback(id.0).into()),
        }
    }

    /// The raw bytes of a read-back buffer (or tightly packed image texels).
    pub fn bytes(&self, id: ReadbackId) -> Result<&[u8]> {
        self.readbacks
            .get(&id.0)
            .map(|(bytes, _)| bytes.as_slice())
            .ok_or_else(|| GraphError::NoSuchReadback(id.0).into())
    }
}

/// Runs compiled graphs: owns the shader library, frames in flight, transient memory and history.
pub struct Executor {
    ctx: Context,
    library: ShaderLibrary,
    timeline: vk::Semaphore,
    submitted: u64,
    slots: Vec<FrameSlot>,
    next_slot: usize,
    frame_index: u64,
    transients: TransientPool,
    temporal: TemporalStore<Arc<Image>, ImageDesc>,
    last_timings: Vec<PassTiming>,
    /// Outputs of frames that completed before their owner asked for them.
    completed: HashMap<u64, FrameOutputs>,
}

impl Executor {
    /// Creates an executor with `ctx.frames_in_flight()` frame slots.
    pub fn new(ctx: &Context, library: ShaderLibrary) -> Result<Self> {
        let mut type_info = vk::SemaphoreTypeCreateInfo::default()
            .semaphore_type(vk::SemaphoreType::TIMELINE)
            .initial_value(0);
        let info = vk::SemaphoreCreateInfo::default().push_next(&mut type_info);
        // SAFETY: device valid.
        let timeline =
            unsafe { ctx.device().create_semaphore(&info, None) }.vk("vkCreateSemaphore")?;
        ctx.set_name(timeline, "frame timeline");
        let mut executor = Self {
            ctx: ctx.clone(),
            library,
            timeline,
            submitted: 0,
            slots: Vec::new(),
            next_slot: 0,
            frame_index: 0,
            transients: TransientPool::default(),
            temporal: TemporalStore::default(),
            last_timings: Vec::new(),
            completed: HashMap::new(),
        };
        for i in 0..ctx.frames_in_flight() {
            executor.slots.push(FrameSlot::new(ctx, i)?);
        }
        Ok(executor)
    }

    /// The shader library (pipelines, reflection, hot reload).
    pub fn library(&self) -> &ShaderLibrary {
        &self.library
    }

    /// The context.
    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// GPU time per pass of the last completed frame.
    pub fn pass_timings(&self) -> &[PassTiming] {
        &self.last_timings
    }

    /// The index the next frame will have.
    pub fn frame_index(&self) -> u64 {
        self.frame_index
    }

    /// Invalidates every history resource (they are cleared before next use).
    pub fn reset_history(&mut self) {
        self.temporal.reset_all();
    }

    /// Invalidates one history resource.
    pub fn reset_history_key(&mut self, key: &str) {
        self.temporal.reset(key);
    }

    fn wait_value(&self, value: u64, during: &str) -> Result<()> {
        if value == 0 {
            return Ok(());
        }
        if self.ctx.is_device_lost() {
            return Err(self.ctx.device_lost_error(during));
        }
        let semaphores = [self.timeline];
        let values = [value];
        let info = vk::SemaphoreWaitInfo::default()
            .semaphores(&semaphores)
            .values(&values);
        let limit = self.ctx.info().kind.wait_limit();
        // SAFETY: the timeline semaphore is valid.
        unsafe {
            self.ctx
                .device()
                .wait_semaphores(&info, limit.as_nanos() as u64)
        }
        .map_err(|e| match e {
            vk::Result::TIMEOUT => EngineError::Timeout {
                during: during.to_string(),
                seconds: limit.as_secs(),
            },
            vk::Result::ERROR_DEVICE_LOST => self.ctx.observe(EngineError::DeviceLost {
                during: during.to_string(),
            }),
            other => crate::error::from_vk("vkWaitSemaphores", other),
        })
    }

    /// Waits for every submitted frame; their outputs stay available to [`Executor::wait`].
    pub fn wait_all(&mut self) -> Result<()> {
        self.wait_value(self.submitted, "waiting for all frames")?;
        for i in 0..self.slots.len() {
            let (value, fresh) = (self.slots[i].value, !self.slots[i].collected);
            let outputs = self.collect(i)?;
            if fresh {
                self.completed.insert(value, outputs);
            }
        }
        Ok(())
    }

    /// Reads a completed slot's timings, releases what it kept alive; returns its readbacks.
    fn collect(&mut self, slot_index: usize) -> Result<FrameOutputs> {
        let slot = &mut self.slots[slot_index];
        if slot.collected {
            return Ok(FrameOutputs::default());
        }
        slot.collected = true;
        let mut outputs = FrameOutputs::default();
        if self.ctx.info().timestamps && !slot.pass_names.is_empty() {
            let count = slot.pass_names.len() * 2;
            let mut stamps = vec![0u64; count];
            // SAFETY: the frame completed; the queries were written.
            unsafe {
                self.ctx.device().get_query_pool_results(
                    slot.queries,
                    0,
                    &mut stamps,
                    vk::QueryResultFlags::TYPE_64,
                )
            }
            .vk("vkGetQueryPoolResults")?;
            let period = self.ctx.info().timestamp_period_ns as f64;
            outputs.timings = slot
                .pass_names
                .iter()
                .enumerate()
                .map(|(i, name)| PassTiming {
                    name: name.clone(),
                    ms: stamps[2 * i + 1].saturating_sub(stamps[2 * i]) as f64 * period / 1e6,
                    start_ms: stamps[2 * i].saturating_sub(stamps[0]) as f64 * period / 1e6,
                })
                .collect();
            self.last_timings = outputs.timings.clone();
        }
        for r in slot.readbacks.drain(..) {
            outputs
                .readbacks
                .insert(r.index, (r.buffer.mapped()?.to_vec(), r.image));
        }
        slot.release();
        Ok(outputs)
    }

    /// Waits for `frame` and returns its outputs (readbacks, pass timings). Each frame's outputs can
    /// be taken once; a frame whose slot was reused since is an error.
    pub fn wait(&mut self, frame: FrameId) -> Result<FrameOutputs> {
        if let Some(outputs) = self.completed.remove(&frame.0) {
            return Ok(outputs);
        }
        let slot = self
            .slots
            .iter()
            .position(|s| s.value == frame.0)
            .ok_or_else(|| {
                EngineError::InvalidArgument(format!(
                    "frame {} is no longer in flight; wait for a frame before submitting {} more",
                    frame.0,
                    self.slots.len()
                ))
            })?;
        if self.slots[slot].collected {
            return Err(EngineError::InvalidArgument(format!(
                "the outputs of frame {} were already taken",
                frame.0
            )));
        }
        self.wait_value(frame.0, &format!("waiting for frame {}", frame.0))?;
        self.collect(slot)
    }

    /// Records and submits a compiled graph. Returns at once; [`Executor::wait`] gives its outputs.
    pub fn execute(&mut self, graph: CompiledGraph) -> Result<FrameId> {
        self.execute_with(graph, &SubmitOptions::default())
    }

    /// Like [`Executor::execute`], waiting on and signalling the given semaphores.
    pub fn execute_with(
        &mut self,
        graph: CompiledGraph,
        submit: &SubmitOptions,
    ) -> Result<FrameId> {
        let slot_index = self.next_slot;
        let previous = self.slots[slot_index].value;
        self.wait_value(previous, "waiting for a free frame slot")?;
        // A previous frame in this slot whose outputs were not taken yet: keep them for `wait`.
        if !self.slots[slot_index].collected {
            let outputs = self.collect(slot_index)?;
            self.completed.insert(previous, outputs);
        }
        // Outputs nobody asked for within a few frames are dropped.
        let oldest_kept = self.submitted.saturating_sub(4 * self.slots.len() as u64);
        self.completed.retain(|&value, _| value > oldest_kept);

        if !self.transients.matches(&graph.plan) {
            self.wait_all()?;
            self.transients.rebuild(&self.ctx, &graph.plan)?;
        }
        let mut physical = self.transients.physical(&graph.plan);
        for (id, external) in &graph.externals {
            let resource = &graph.plan.resources[id.0 as usize];
            match external {
                External::Image(image) => {
                    check_usage_image(resource.name.as_str(), image, resource.image_usage)?;
                    physical.insert(*id, Physical::Image(image.clone()));
                }
                External::Buffer(buffer) => {
                    physical.insert(*id, Physical::Buffer(buffer.clone()));
                }
                External::Described => {
                    if resource.lifetime.is_some() {
                        return Err(GraphError::DescribedOnly(resource.name.clone()).into());
                    }
                }
            }
        }
        let (history_valid, clears) = self.bind_temporal(&graph.plan, &mut physical)?;

        let value = self.submitted + 1;
        let result = self.record(slot_index, graph, &physical, &history_valid, &clears);
        let slot = &mut self.slots[slot_index];
        if let Err(e) = result {
            slot.release();
            slot.readbacks.clear();
            return Err(e);
        }
        let cmds = [vk::CommandBufferSubmitInfo::default().command_buffer(slot.cmd)];
        let mut signals = vec![vk::SemaphoreSubmitInfo::default()
            .semaphore(self.timeline)
            .value(value)
            .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
        signals.extend(submit.signal.iter().map(|&s| {
            vk::SemaphoreSubmitInfo::default()
                .semaphore(s)
                .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
        }));
        let waits: Vec<vk::SemaphoreSubmitInfo> = submit
            .wait
            .iter()
            .map(|&(s, stage)| {
                vk::SemaphoreSubmitInfo::default()
                    .semaphore(s)
                    .stage_mask(stage)
            })
            .collect();
        let info = [vk::SubmitInfo2::default()
            .command_buffer_infos(&cmds)
            .wait_semaphore_infos(&waits)
            .signal_semaphore_infos(&signals)];
        if let Err(e) = self.ctx.submit_frame(&info) {
            let e = match e {
                EngineError::DeviceLost { .. } => self.ctx.device_lost_error(format!(
                    "the submission of frame {value} (passes {})",
                    slot.pass_names.join(", ")
                )),
                other => other,
            };
            slot.release();
            slot.readbacks.clear();
            return Err(e);
        }
        slot.value = value;
        slot.collected = false;
        self.submitted = value;
        self.next_slot = (slot_index + 1) % self.slots.len();
        self.frame_index += 1;
        self.temporal.end_frame();
        Ok(FrameId(value))
    }

    /// Resolves temporal resources to this frame's physical images; returns which `prev` handles hold
    /// history, and the images to clear first.
    fn bind_temporal(
        &mut self,
        plan: &Plan,
        physical: &mut HashMap<ResourceId, Physical>,
    ) -> Result<TemporalBinding> {
        let mut valid = HashMap::new();
        let mut clears = Vec::new();
        let mut by_key: HashMap<&str, TemporalIds> = HashMap::new();
        for (i, r) in plan.resources.iter().enumerate() {
            let id = ResourceId(i as u32);
            let ResourceDesc::Image(desc) = r.desc else {
                continue;
            };
            match &r.kind {
                ResourceKind::TemporalPrev(key) => {
                    by_key.entry(key).or_insert((None, None, desc)).0 = Some(id)
                }
                ResourceKind::TemporalCur(key) => {
                    by_key.entry(key).or_insert((None, None, desc)).1 = Some(id)
                }
                _ => {}
            }
        }
        let ctx = self.ctx.clone();
        for (key, (prev, cur, desc)) in by_key {
            let slots = self
                .temporal
                .begin(key, desc, |d, i| -> Result<Arc<Image>> {
                    Image::new(
                        &ctx,
                        &format!("{key} [{i}]"),
                        d,
                        vk::ImageUsageFlags::STORAGE
                            | vk::ImageUsageFlags::SAMPLED
                            | vk::ImageUsageFlags::TRANSFER_SRC
                            | vk::ImageUsageFlags::TRANSFER_DST,
                        "graph.history",
                    )
                    .map(Arc::new)
                })?;
            if slots.needs_clear {
                clears.push(slots.prev.clone());
                clears.push(slots.cur.clone());
            }
            if let Some(prev) = prev {
                physical.insert(prev, Physical::Image(slots.prev.clone()));
                valid.insert(prev, slots.valid);
            }
            if let Some(cur) = cur {
                physical.insert(cur, Physical::Image(slots.cur.clone()));
            }
        }
        Ok((valid, clears))
    }

    fn record(
        &mut self,
        slot_index: usize,
        graph: CompiledGraph,
        physical: &HashMap<ResourceId, Physical>,
        history_valid: &HashMap<ResourceId, bool>,
        clears: &[Arc<Image>],
    ) -> Result<()> {
        let ctx = self.ctx.clone();
        let device = ctx.device();
        let timestamps = ctx.info().timestamps;
        let CompiledGraph {
            plan,
            work,
            readbacks,
            ..
        } = graph;
        let slot = &mut self.slots[slot_index];
        slot.ensure_queries(&ctx, (plan.passes.len() * 2) as u32)?;
        // SAFETY: the slot's previous frame completed (waited above).
        unsafe { device.reset_command_pool(slot.pool, vk::CommandPoolResetFlags::empty()) }
            .vk("vkResetCommandPool")?;
        let begin = vk::CommandBufferBeginInfo::default()
            .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
        // SAFETY: the command buffer was reset with its pool.
        unsafe { device.begin_command_buffer(slot.cmd, &begin) }.vk("vkBeginCommandBuffer")?;
        let cmd = slot.cmd;
        if timestamps {
            // SAFETY: cmd is recording; the pool has query_capacity queries.
            unsafe { device.cmd_reset_query_pool(cmd, slot.queries, 0, slot.query_capacity) };
        }
        record_clears(&ctx, cmd, clears);

        let names: Vec<String> = plan.resources.iter().map(|r| r.name.clone()).collect();
        let mut readback_buffers = Vec::new();
        slot.pass_names.clear();
        for (position, (pass, work)) in plan.passes.iter().zip(work).enumerate() {
            ctx.begin_label(cmd, &pass.name);
            record_barriers(
                &ctx,
                cmd,
                &plan,
                &pass.barriers,
                physical,
                &self.transients.slot_states,
            )?;
            if timestamps {
                // SAFETY: query index within capacity.
                unsafe {
                    device.cmd_write_timestamp2(
                        cmd,
                        vk::PipelineStageFlags2::ALL_COMMANDS,
                        slot.queries,
                        (2 * position) as u32,
                    )
                };
            }
            match work {
                PassWork::Callback(record) => {
                    let mut pcx = PassContext {
                        ctx: &ctx,
                        cmd,
                        library: &self.library,
                        physical,
                        names: &names,
                        accesses: &pass.accesses,
                        pass_name: &pass.name,
                        keep_alive: &mut slot.pipelines,
                        history_valid,
                        frame_index: self.frame_index,
                    };
                    record(&mut pcx)?;
                }
                PassWork::Readback => {
                    let (id, _, _) = pass.accesses[0];
                    let index = graph_readback_index(&readbacks, pass.decl_index);
                    let pending = record_readback(&ctx, cmd, &plan, id, physical, index)?;
                    readback_buffers.push(pending);
                }
                PassWork::Missing => return Err(GraphError::NoWork(pass.name.clone()).into()),
            }
            if timestamps {
                // SAFETY: as above.
                unsafe {
                    device.cmd_write_timestamp2(
                        cmd,
                        vk::PipelineStageFlags2::ALL_COMMANDS,
                        slot.queries,
                        (2 * position + 1) as u32,
                    )
                };
            }
            ctx.end_label(cmd);
            slot.pass_names.push(pass.name.clone());
        }
        if !readback_buffers.is_empty() {
            let to_host = [vk::MemoryBarrier2::default()
                .src_stage_mask(vk::PipelineStageFlags2::COPY)
                .src_access_mask(vk::AccessFlags2::TRANSFER_WRITE)
                .dst_stage_mask(vk::PipelineStageFlags2::HOST)
                .dst_access_mask(vk::AccessFlags2::HOST_READ)];
            // SAFETY: cmd is recording.
            unsafe {
                device.cmd_pipeline_barrier2(
                    cmd,
                    &vk::DependencyInfo::default().memory_barriers(&to_host),
                )
            };
        }
        // SAFETY: cmd is recording.
        unsafe { device.end_command_buffer(cmd) }.vk("vkEndCommandBuffer")?;

        // The frame is recorded: publish the states it leaves resources in.
        for &(id, state) in &plan.final_states {
            match physical.get(&id) {
                Some(Physical::Image(image)) => image.set_tracked_state(state),
                Some(Physical::Buffer(buffer)) => buffer.set_tracked_state(state),
                None => {}
            }
        }
        for (s, state) in plan.slot_final_states.iter().enumerate() {
            if let Some(slot_state) = self.transients.slot_states.get_mut(s) {
                *slot_state = *state;
            }
        }
        slot.resources = physical.values().cloned().collect();
        slot.readbacks = readback_buffers;
        Ok(())
    }
}

fn graph_readback_index(readbacks: &[(usize, ResourceId)], decl_index: usize) -> usize {
    readbacks
        .iter()
        .position(|&(pass, _)| pass == decl_index)
        .unwrap_or(usize::MAX)
}

fn check_usage_image(name: &str, image: &Image, needed: vk::ImageUsageFlags) -> Result<()> {
    let missing = needed & !image.usage();
    if missing.is_empty() {
        Ok(())
    } else {
        Err(GraphError::ImportUsage {
            resource: name.to_string(),
            missing: format!("{missing:?}"),
        }
        .into())
    }
}

/// Clears new or reset history images to zero, leaving them in `TRANSFER_DST_OPTIMAL`.
fn record_clears(ctx: &Context, cmd: vk::CommandBuffer, images: &[Arc<Image>]) {
    if images.is_empty() {
        return;
    }
    let device = ctx.device();
    let to_dst: Vec<vk::ImageMemoryBarrier2> = images
        .iter()
        .map(|image| {
            let state = image.tracked_state();
            vk::ImageMemoryBarrier2::default()
                .src_stage_mask(state.stage)
                .src_access_mask(state.access)
                .dst_stage_mask(vk::PipelineStageFlags2::CLEAR)
                .dst_access_mask(vk::AccessFlags2::TRANSFER_WRITE)
                .old_layout(vk::ImageLayout::UNDEFINED)
                .new_layout(vk::ImageLayout::TRANSFER_DST_OPTIMAL)
                .image(image.raw())
                .subresource_range(color_range())
        })
        .collect();
    // SAFETY: cmd is recording; images are alive for the frame.
    unsafe {
        device.cmd_pipeline_barrier2(
            cmd,
            &vk::DependencyInfo::default().image_memory_barriers(&to_dst),
        );
        for image in images {
            device.cmd_clear_color_image(
                cmd,
                image.raw(),
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &vk::ClearColorValue { float32: [0.0; 4] },
                &[color_range()],
            );
        }
    }
    let info = Access::TransferWrite.info();
    for image in images {
        image.set_tracked_state(ResourceState {
            layout: info.layout,
            stage: vk::PipelineStageFlags2::CLEAR,
            access: info.access,
        });
    }
}

fn record_barriers(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    plan: &Plan,
    barriers: &[Barrier],
    physical: &HashMap<ResourceId, Physical>,
    slot_states: &[ResourceState],
) -> Result<()> {
    let mut images = Vec::new();
    let mut buffers = Vec::new();
    for b in barriers {
        let resource = &plan.resources[b.resource.0 as usize];
        let frame_start = || match (&resource.kind, resource.slot, physical.get(&b.resource)) {
            (ResourceKind::Transient, Some(s), _) => {
                slot_states.get(s).copied().unwrap_or_default()
            }
            (_, _, Some(Physical::Image(image))) => image.tracked_state(),
            (_, _, Some(Physical::Buffer(buffer))) => buffer.tracked_state(),
            _ => ResourceState::default(),
        };
        let (src_stage, src_access, start_layout) = match b.src {
            BarrierSrc::FrameStart => {
                let state = frame_start();
                (state.stage, state.access, state.layout)
            }
            BarrierSrc::Earlier { stage, access } => (stage, access, vk::ImageLayout::UNDEFINED),
        };
        match physical.get(&b.resource) {
            Some(Physical::Image(image)) => images.push(
                vk::ImageMemoryBarrier2::default()
                    .src_stage_mask(src_stage)
                    .src_access_mask(src_access)
                    .dst_stage_mask(b.dst_stage)
                    .dst_access_mask(b.dst_access)
                    .old_layout(b.old_layout.unwrap_or(start_layout))
                    .new_layout(b.new_layout)
                    .image(image.raw())
                    .subresource_range(color_range()),
            ),
            Some(Physical::Buffer(buffer)) => buffers.push(
                vk::BufferMemoryBarrier2::default()
                    .src_stage_mask(src_stage)
                    .src_access_mask(src_access)
                    .dst_stage_mask(b.dst_stage)
                    .dst_access_mask(b.dst_access)
                    .buffer(buffer.raw())
                    .size(vk::WHOLE_SIZE),
            ),
            None => {
                return Err(EngineError::InvalidArgument(format!(
                    "resource {} has no physical resource",
                    resource.name
                )))
            }
        }
    }
    if !images.is_empty() || !buffers.is_empty() {
        let info = vk::DependencyInfo::default()
            .image_memory_barriers(&images)
            .buffer_memory_barriers(&buffers);
        // SAFETY: cmd is recording; all resources are alive for the frame.
        unsafe { ctx.device().cmd_pipeline_barrier2(cmd, &info) };
    }
    Ok(())
}

/// Copies a resource into a new host-visible buffer.
fn record_readback(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    plan: &Plan,
    id: ResourceId,
    physical: &HashMap<ResourceId, Physical>,
    index: usize,
) -> Result<PendingReadback> {
    let resource = &plan.resources[id.0 as usize];
    let size = resource.desc.byte_size().max(4);
    let buffer = Arc::new(Buffer::new(
        ctx,
        &BufferDesc {
            name: format!("readback {}", resource.name),
            size,
            usage: vk::BufferUsageFlags::TRANSFER_DST,
            location: MemoryLocation::GpuToCpu,
            category: "readback",
        },
    )?);
    let device = ctx.device();
    let image = match physical.get(&id) {
        Some(Physical::Image(image)) => {
            let desc = image.desc();
            let region = vk::BufferImageCopy::default()
                .image_subresource(vk::ImageSubresourceLayers {
                    aspect_mask: vk::ImageAspectFlags::COLOR,
                    mip_level: 0,
                    base_array_layer: 0,
                    layer_count: 1,
                })
                .image_extent(desc.extent());
            // SAFETY: cmd is recording; the image is in TRANSFER_SRC_OPTIMAL (barrier above).
            unsafe {
                device.cmd_copy_image_to_buffer(
                    cmd,
                    image.raw(),
                    vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                    buffer.raw(),
                    &[region],
                )
            };
            Some(desc)
        }
        Some(Physical::Buffer(source)) => {
            let region = vk::BufferCopy::default().size(source.size().min(size));
            // SAFETY: cmd is recording; both buffers are alive.
            unsafe { device.cmd_copy_buffer(cmd, source.raw(), buffer.raw(), &[region]) };
            None
        }
        None => {
            return Err(EngineError::InvalidArgument(format!(
                "readback of {} without a physical resource",
                resource.name
            )))
        }
    };
    Ok(PendingReadback {
        index,
        buffer,
        image,
    })
}

impl Drop for Executor {
    fn drop(&mut self) {
        if self.ctx.is_device_lost() {
            // Waits for what the device still runs (an injected loss leaves it working); a lost
            // device returns at once.
            let _ = self.ctx.wait_idle();
        } else if let Err(e) = self.wait_value(self.submitted, "dropping the executor") {
            tracing::error!("{e}");
            let _ = self.ctx.wait_idle();
        }
        for slot in &mut self.slots {
            slot.destroy(&self.ctx);
        }
        self.temporal.clear();
        // SAFETY: every frame completed; the semaphore is unused.
        unsafe { self.ctx.device().destroy_semaphore(self.timeline, None) };
    }
}
