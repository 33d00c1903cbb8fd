//! Path tracing: next-event estimation with multiple importance sampling, Russian roulette,
//! N samples per pixel (`shaders/path_trace/path_trace.comp`, `path_trace_in_workgroup.comp` for
//! a scene walked in workgroup memory, `path_trace_surfaces.comp` where the denoiser's images are
//! written with more than one sample a pixel, `shaders/common/path.glsl`);
//! replays
//! last frame's paths where asked ([`Replay`]); one dispatch per batch of samples
//! ([`sample_batches`]). With one sample a pixel, the paths Russian roulette keeps past its first
//! segments are parked and continued over a compacted list ([`parking`],
//! [`Config::park_depth`]; `shaders/path_trace/long_paths.comp`).

use crate::light_transport::{
    parking, sample_batches, Frame, Images, Outputs, Replay, ReplayParams, SampleBatch,
};
use crate::plumbing::placeholder::add_zero_image;
use crate::plumbing::scene_buffers::{scene_in_workgroup, SceneHandles};
use crate::samples_per_pixel::SamplesPerPixel;
use crate::shaders::path_trace::{
    LONG_PATHS, PATH_TRACE, PATH_TRACE_IN_WORKGROUP, PATH_TRACE_SURFACES,
};
use lucid_engine::graph::{BufferHandle, ComputePass, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::Specialization;

/// The path tracer's push constants (`Push` in `shaders/path_trace/path_trace.glsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct Push {
    replay: ReplayParams,
    batch: SampleBatch,
}

/// How the path tracer runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Config {
    /// With one sample a pixel, paths still alive after this many segments are parked and
    /// continued by a second kernel over a compacted list ([`parking`]); `None`, or with more
    /// samples a pixel or more pixels than 1920x1080 (128 MiB of parked paths), one kernel traces
    /// every path to its end.
    pub park_depth: Option<u32>,
}

/// Adds the path tracer at `sampling`'s size and samples per pixel, reading the scene and the
/// frame constants; the pixels `replay` picks replay last frame's paths (without it the pass does
/// not depend on the G-buffer); the denoiser's images are written when `sampling.surface`.
pub fn add_path_trace(
    g: &mut RenderGraph,
    (scene, frame, spec): (&SceneHandles, BufferHandle, &Specialization),
    replay: Option<&Replay>,
    sampling: Frame,
    config: &Config,
) -> Outputs {
    let (width, height, surface) = (sampling.width, sampling.height, sampling.surface);
    let stats = crate::plumbing::stats::add_counter(g, "path_trace.stats");
    let parking = parking::Parking::clear(g, "path_trace", config.park_depth, &sampling);
    let motion = match replay {
        Some(r) => r.motion,
        // Bound, never read: nothing is replayed, and the pass does not wait for the G-buffer.
        None => add_zero_image(g, "path_trace.no_motion", ImageDesc::rgba16f(1, 1)),
    };
    // With one sample a pixel the first hit's albedo and emission go straight to the denoiser's
    // images, and the shader without the denoiser's workgroup memory writes them.
    let one_sample = sampling.samples_per_pixel == SamplesPerPixel::ONE;
    let shader = if surface && !one_sample {
        &PATH_TRACE_SURFACES
    } else if scene_in_workgroup(spec) {
        &PATH_TRACE_IN_WORKGROUP
    } else {
        &PATH_TRACE
    };
    let mut pass = g.compute_pass("path_trace", shader);
    scene.read(&mut pass);
    pass.specialization(spec)
        .read("b_frame", frame)
        .specialize("ONE_SAMPLE", one_sample);
    let stats = pass.read_write("b_stats", stats);
    pass.read("u_motion", motion);
    let replay = replay.map_or(ReplayParams::default(), |r| r.params);
    let images = Images::create(&mut pass, "path_trace", (width, height), surface);
    pass.create_buffer(
        "b_rng_state",
        "path_trace.rng_state",
        u64::from(width * height) * 4,
    );
    let parked = parking::bind(&mut pass, "path_trace", parking);
    let pushes = sample_batches(sampling.samples_per_pixel)
        .into_iter()
        .map(|batch| Push { replay, batch })
        .collect();
    pass.dispatch_each([width, height, 1], pushes);
    let (images, stats) = match parked {
        Some(parked) => {
            let inputs = |pass: &mut ComputePass<'_>| {
                scene.read(pass);
                pass.specialization(spec).read("b_frame", frame);
            };
            parking::add_continuation(g, &LONG_PATHS, inputs, parked, (images, stats))
        }
        None => (images, stats),
    };
    images.with_stats(stats)
}
