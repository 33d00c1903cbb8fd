//! The wavefront path tracer's five kernels, each added as a compute pass that declares and binds
//! what its shader (`shaders/wavefront/`) reads and writes: generate and accumulate over the
//! pixels, extend, shade and shadow over a queue, dispatched indirectly from its length (extend
//! and shade in their material-binning variants when asked).

use super::queues::{self, MAX_PATHS};
use super::state::WaveBuffers;
use crate::light_transport::{Images, ReplayParams};
use crate::plumbing::scene_buffers::SceneHandles;
use crate::shaders::wavefront::{
    ACCUMULATE, EXTEND, EXTEND_BINNED, GENERATE, SHADE, SHADE_BINNED, SHADOW,
};
use lucid_engine::error::EngineError;
use lucid_engine::graph::{BufferHandle, ComputePass, ImageHandle, RenderGraph};
use lucid_engine::shader::{ShaderSource, Specialization};

/// Push constants of the generate kernel (`Push` in `generate.comp`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct GeneratePush {
    replay: ReplayParams,
    sample_index: u32,
    slots: u32,
    counters: u32,
}

/// Push constants of the accumulate kernel (`Push` in `accumulate.comp`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct AccumulatePush {
    sample_index: u32,
    slots: u32,
}

/// Push constants of the kernels over a queue (`Push` in `extend.glsl`, `shade.glsl`,
/// `shadow.comp`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct DepthPush {
    depth: u32,
}

/// What the kernels are given: the scene, the frame constants and their specialization, and the
/// frame's size and options.
#[derive(Clone, Copy)]
pub struct Inputs<'a> {
    /// The scene's buffers.
    pub scene: &'a SceneHandles,
    /// The frame constants (`b_frame`).
    pub frame: BufferHandle,
    /// The scene's specialization constants.
    pub spec: &'a Specialization,
    /// Image size in pixels (a path per pixel).
    pub size: (u32, u32),
    /// Longest path in segments.
    pub max_depth: u32,
    /// Whether the denoiser's images are written (`SURFACE_OUTPUTS`).
    pub surface: bool,
    /// Whether extend bins the hits by material for shade (`extend_binned`, `shade_binned`).
    pub binned: bool,
    /// Which pixels replay last frame's paths, and the motion vectors that lead them there (a
    /// placeholder never read when nothing replays).
    pub replay: (ReplayParams, ImageHandle),
}

impl Inputs<'_> {
    fn pass<'g>(
        &self,
        g: &'g mut RenderGraph,
        name: &str,
        shader: &ShaderSource,
    ) -> ComputePass<'g> {
        let mut pass = g.compute_pass(&format!("wavefront.{name}"), shader);
        self.scene.read(&mut pass);
        pass.specialization(self.spec)
            .specialize("SURFACE_OUTPUTS", self.surface)
            .read("b_frame", self.frame);
        pass
    }

    fn paths(&self) -> u64 {
        u64::from(self.size.0) * u64::from(self.size.1)
    }
}

/// Adds sample `sample_index`'s camera rays, resetting the queues.
pub fn add_generate(
    g: &mut RenderGraph,
    inputs: &Inputs<'_>,
    b: &mut WaveBuffers,
    sample_index: u32,
) {
    let mut pass = inputs.pass(g, "generate", &GENERATE);
    let paths = inputs.paths();
    pass.require(move |_| {
        if paths <= MAX_PATHS {
            return Ok(());
        }
        Err(EngineError::InvalidArgument(format!(
            "wavefront path tracing traces at most {MAX_PATHS} paths at once (a queue's workgroups \
             must fit in the {} every device dispatches in x), not {paths}: use a smaller image",
            MAX_PATHS / u64::from(queues::QUEUE_GROUP),
        )))
    });
    for (binding, buffer) in &mut b.path_state {
        if *binding == "b_path_rng" && sample_index > 0 {
            buffer.read_write(&mut pass, binding);
        } else {
            buffer.write(&mut pass, binding);
        }
    }
    b.ray_queues[0].write(&mut pass, "b_ray_queue");
    b.counts.write(&mut pass, "b_counts");
    b.args[0].write(&mut pass, "b_args_even");
    b.args[1].write(&mut pass, "b_args_odd");
    pass.read("u_motion", inputs.replay.1);
    pass.push(&GeneratePush {
        replay: inputs.replay.0,
        sample_index,
        slots: queues::slots(inputs.max_depth),
        counters: queues::counters(inputs.max_depth, inputs.binned),
    });
    pass.dispatch([inputs.size.0, inputs.size.1, 1]);
}

/// Adds the closest-hit search of bounce `depth`'s ray queue.
pub fn add_extend(g: &mut RenderGraph, inputs: &Inputs<'_>, b: &mut WaveBuffers, depth: u32) {
    let shader = if inputs.binned {
        &EXTEND_BINNED
    } else {
        &EXTEND
    };
    let mut pass = inputs.pass(g, "extend", shader);
    let queue = (depth % 2) as usize;
    b.state("b_ray_origin").read(&mut pass, "b_ray_origin");
    b.state("b_ray_direction")
        .read(&mut pass, "b_ray_direction");
    b.ray_queues[queue].read(&mut pass, "b_ray_queue");
    b.hits.write(&mut pass, "b_hits");
    if inputs.binned {
        b.counts.read_write(&mut pass, "b_counts");
        b.binned_queue.write(&mut pass, "b_binned_queue");
    } else {
        b.counts.read(&mut pass, "b_counts");
    }
    pass.push(&DepthPush { depth });
    let slot = queues::ray_slot(depth);
    pass.dispatch_indirect(
        b.args[queues::args_buffer(slot)].latest(),
        queues::args_offset(slot),
    );
}

/// Adds the vertex of bounce `depth`: emission, light sample, next direction; fills the bounce's
/// shadow queue and the next bounce's ray queue.
pub fn add_shade(g: &mut RenderGraph, inputs: &Inputs<'_>, b: &mut WaveBuffers, depth: u32) {
    let shader = if inputs.binned { &SHADE_BINNED } else { &SHADE };
    let mut pass = inputs.pass(g, "shade", shader);
    let queue = (depth % 2) as usize;
    for (binding, buffer) in &mut b.path_state {
        buffer.read_write(&mut pass, binding);
    }
    if inputs.binned {
        b.binned_queue.read(&mut pass, "b_binned_queue");
    } else {
        b.ray_queues[queue].read(&mut pass, "b_ray_queue");
    }
    b.hits.read(&mut pass, "b_hits");
    b.counts.read_write(&mut pass, "b_counts");
    let slot = queues::ray_slot(depth);
    let own_args = queues::args_buffer(slot);
    b.args[1 - own_args].read_write(&mut pass, "b_args_out");
    b.shadow_queue.write(&mut pass, "b_shadow_queue");
    b.shadow_rays.write(&mut pass, "b_shadow_rays");
    b.ray_queues[1 - queue].write(&mut pass, "b_next_ray_queue");
    pass.push(&DepthPush { depth });
    pass.dispatch_indirect(b.args[own_args].latest(), queues::args_offset(slot));
}

/// Adds the occlusion tests of bounce `depth`'s shadow queue.
pub fn add_shadow(g: &mut RenderGraph, inputs: &Inputs<'_>, b: &mut WaveBuffers, depth: u32) {
    let mut pass = inputs.pass(g, "shadow", &SHADOW);
    b.state("b_path_radiance")
        .read_write(&mut pass, "b_path_radiance");
    b.counts.read(&mut pass, "b_counts");
    b.shadow_queue.read(&mut pass, "b_shadow_queue");
    b.shadow_rays.read(&mut pass, "b_shadow_rays");
    pass.push(&DepthPush { depth });
    let slot = queues::shadow_slot(depth);
    pass.dispatch_indirect(
        b.args[queues::args_buffer(slot)].latest(),
        queues::args_offset(slot),
    );
}

/// Adds sample `sample_index`'s paths to the images (creating them on the first sample, which
/// `images` is `None` before); returns them.
pub fn add_accumulate(
    g: &mut RenderGraph,
    inputs: &Inputs<'_>,
    b: &mut WaveBuffers,
    (images, stats): (Option<Images>, BufferHandle),
    sample_index: u32,
) -> (Images, BufferHandle) {
    let mut pass = inputs.pass(g, "accumulate", &ACCUMULATE);
    for binding in ["b_path_radiance", "b_first_hit"] {
        b.state(binding).read(&mut pass, binding);
    }
    b.counts.read(&mut pass, "b_counts");
    let stats = pass.read_write("b_stats", stats);
    let images = match images {
        None => Images::create(&mut pass, "wavefront", inputs.size, inputs.surface),
        Some(mut images) => {
            images.radiance = pass.read_write("u_radiance", images.radiance);
            let s = &mut images.surface;
            s.demodulated = pass.read_write("u_demodulated", s.demodulated);
            s.albedo = pass.read_write("u_albedo", s.albedo);
            s.emission = pass.read_write("u_emission", s.emission);
            images
        }
    };
    pass.push(&AccumulatePush {
        sample_index,
        slots: queues::slots(inputs.max_depth),
    });
    pass.dispatch([inputs.size.0, inputs.size.1, 1]);
    (images, stats)
}
