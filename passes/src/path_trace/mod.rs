//! Path tracing: next-event estimation with multiple importance sampling, Russian roulette,
//! N samples per pixel, with path regeneration (`shaders/path_trace/path_trace.comp`,
//! `shaders/common/path.glsl`).

use crate::scene_buffers::SceneHandles;
use crate::shaders::path_trace::PATH_TRACE;
use crate::transport::{Images, Outputs};
use lucid_engine::graph::{Access, BufferHandle, RenderGraph};
use lucid_engine::shader::Specialization;

/// Threads the path tracer runs by default: enough to fill a large GPU (an H200 keeps about
/// 135 000 of them resident), few enough that each takes several pixels at 1080p, so that
/// threads whose paths end early take more work instead of idling.
pub const DEFAULT_THREADS: u32 = 1 << 18;

/// Pixels handed out as one job run: the shader walks the image in 8x8 tiles.
const TILE_PIXELS: u32 = 64;

/// Adds the path tracer at `width`×`height`, reading the scene and the frame constants, run by
/// `threads` threads (rounded to whole tiles, at most one per pixel; see [`DEFAULT_THREADS`]).
/// The image does not depend on `threads`.
pub fn add(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    frame: BufferHandle,
    spec: &Specialization,
    (width, height): (u32, u32),
    threads: u32,
) -> Outputs {
    let threads = dispatched_threads(width, height, threads);
    let stats = crate::stats::add_counter(g, "path_trace.stats");
    let work = add_work_counter(g, threads);
    let mut p = g.add_pass("path_trace");
    scene.read(&mut p);
    let frame = p.read(frame, Access::ComputeRead);
    let stats = p.write(stats, Access::ComputeReadWrite);
    let work = p.write(work, Access::ComputeReadWrite);
    let images = Images::create(&mut p, "path_trace", width, height);
    let (scene, spec) = (*scene, spec.clone());
    p.execute(move |ctx| {
        let dispatch = ctx
            .compute(&PATH_TRACE)
            .specialization(&spec)
            .buffer("b_frame", frame)
            .buffer("b_stats", stats)
            .buffer("b_work", work)
            .image("u_radiance", images.radiance)
            .image("u_demodulated", images.demodulated)
            .image("u_albedo", images.albedo)
            .image("u_emission", images.emission);
        scene.bind(dispatch).dispatch_threads([threads, 1, 1])
    });
    images.with_stats(stats)
}

/// The threads dispatched for an image: `requested` rounded up to whole tiles, no more than the
/// image's tiles hold, at least one tile.
pub fn dispatched_threads(width: u32, height: u32, requested: u32) -> u32 {
    let jobs = width.div_ceil(8) * height.div_ceil(8) * TILE_PIXELS;
    requested
        .max(1)
        .div_ceil(TILE_PIXELS)
        .saturating_mul(TILE_PIXELS)
        .min(jobs)
}

/// Adds a pass creating the job counter, starting at `threads` (job `i < threads` is thread
/// `i`'s first).
fn add_work_counter(g: &mut RenderGraph, threads: u32) -> BufferHandle {
    let mut p = g.add_pass("path_trace.work.clear");
    let work = p.create_buffer("path_trace.work", 16);
    let work = p.write(work, Access::TransferWrite);
    p.execute(move |ctx| ctx.fill_buffer(work, threads));
    work
}

#[cfg(test)]
mod tests {
    use super::dispatched_threads;

    #[test]
    fn threads_are_whole_tiles_and_never_more_than_the_image_needs() {
        assert_eq!(dispatched_threads(1920, 1080, 1 << 18), 1 << 18);
        assert_eq!(dispatched_threads(64, 64, 1 << 18), 4096);
        assert_eq!(dispatched_threads(65, 64, 1 << 18), 9 * 8 * 64);
        assert_eq!(dispatched_threads(64, 64, 100), 128);
        assert_eq!(dispatched_threads(64, 64, 0), 64);
    }
}
