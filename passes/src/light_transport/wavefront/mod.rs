//! Wavefront path tracing: the path tracer's estimator (`trace_path` in
//! `shaders/common/path.glsl`: next-event estimation with MIS, BSDF sampling, Russian roulette,
//! the same random numbers) split into kernels over queues of paths (Laine, Karras and Aila 2013,
//! "Megakernels considered harmful"), one compute pass each (`shaders/wavefront/`). Per sample:
//! **generate** (a camera ray per pixel into the path state, every path in the first ray queue),
//! then per bounce **extend** (closest hits of the ray queue), **shade** (emission, the light
//! sample into the shadow queue, the next direction and Russian roulette into the next ray queue)
//! and **shadow** (occlusion tests, adding the light samples that arrive), then **accumulate**
//! (the paths into the images; the last sample writes the averages). The samples of a frame run
//! one wave after the other, each a path per pixel, because a pixel's sample starts its random
//! numbers where its previous sample's path left them, as in the megakernel: the two draw the
//! same numbers for every path and give the same image.
//!
//! The queue kernels are dispatched indirectly: shade counts the workgroups each queue needs as it
//! appends ([`queues`]), and the graph orders each dispatch after that pass through the
//! indirect-command read ([`lucid_engine::graph::ComputePass::dispatch_indirect`]), so a bounce
//! whose paths have mostly ended launches only the workgroups its queues fill. The host records
//! every bounce up to the longest path (it does not read the lengths back): a bounce with empty
//! queues dispatches no workgroups.
//!
//! With [`Config::bin_by_material`] extend also sorts the hits into bins by material kind and
//! shade walks the bins (`--algo pt-wavefront-binned`).
//!
//! Like the megakernel, it replays last frame's paths where SVGF asks ([`Replay`]; generate
//! starts a picked pixel's path from last frame's pixel, camera and random numbers).

mod kernels;
mod queues;
mod state;

use crate::light_transport::{Frame, Outputs, Replay, ReplayParams};
use crate::plumbing::placeholder::add_zero_image;
use crate::plumbing::scene_buffers::SceneHandles;
use kernels::Inputs;
use lucid_engine::graph::{BufferHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::Specialization;
use state::WaveBuffers;

/// How the wavefront orders its work.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Config {
    /// Extend sorts each bounce's hits into bins by what they hit (a miss, or the material's
    /// kind) and shade walks the bins one after the other, so that a workgroup mostly shades one
    /// kind of material (`extend_binned`, `shade_binned`); the image is the same.
    pub bin_by_material: bool,
}

/// Adds wavefront path tracing at `sampling`'s size, samples per pixel and longest path, reading
/// the scene and the frame constants; the pixels `replay` picks replay last frame's paths
/// (without it the passes do not depend on the G-buffer); the denoiser's images are written when
/// `sampling.surface`.
pub fn add_wavefront(
    g: &mut RenderGraph,
    (scene, frame, spec): (&SceneHandles, BufferHandle, &Specialization),
    replay: Option<&Replay>,
    sampling: Frame,
    config: &Config,
) -> Outputs {
    let replay = match replay {
        Some(r) => (r.params, r.motion),
        // Bound, never read: nothing is replayed, and the passes do not wait for the G-buffer.
        None => (
            ReplayParams::default(),
            add_zero_image(g, "wavefront.no_motion", ImageDesc::rgba16f(1, 1)),
        ),
    };
    let inputs = Inputs {
        scene,
        frame,
        spec,
        size: (sampling.width, sampling.height),
        max_depth: sampling.max_depth,
        surface: sampling.surface,
        binned: config.bin_by_material,
        replay,
    };
    let paths = u64::from(sampling.width) * u64::from(sampling.height);
    let mut buffers = WaveBuffers::new(
        paths,
        sampling.max_depth,
        sampling.surface,
        config.bin_by_material,
    );
    let mut stats = crate::plumbing::stats::add_counter(g, "wavefront.stats");
    let mut images = None;
    for sample_index in 0..sampling.samples_per_pixel.get() {
        kernels::add_generate(g, &inputs, &mut buffers, sample_index);
        for depth in 0..sampling.max_depth {
            kernels::add_extend(g, &inputs, &mut buffers, depth);
            kernels::add_shade(g, &inputs, &mut buffers, depth);
            // The last vertex only adds what it emits (trace_path's loop ends there).
            if depth + 1 < sampling.max_depth {
                kernels::add_shadow(g, &inputs, &mut buffers, depth);
            }
        }
        let (written, counted) =
            kernels::add_accumulate(g, &inputs, &mut buffers, (images, stats), sample_index);
        images = Some(written);
        stats = counted;
    }
    images
        .expect("at least one sample per pixel")
        .with_stats(stats)
}
