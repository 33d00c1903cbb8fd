//! Path tracing: next-event estimation with multiple importance sampling, Russian roulette,
//! N samples per pixel (`shaders/path_trace/path_trace.comp`).

use crate::scene_buffers::SceneHandles;
use crate::shaders::path_trace::PATH_TRACE;
use lucid_engine::graph::{Access, BufferHandle, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::Specialization;

/// What the path tracer produces.
#[derive(Clone, Copy, Debug)]
pub struct Outputs {
    /// Noisy radiance (RGB, alpha 1).
    pub radiance: ImageHandle,
    /// Radiance divided by the first-hit albedo, for denoisers.
    pub demodulated: ImageHandle,
    /// `[non-finite samples dropped, rays traced, 0, 0]` as u32.
    pub stats: BufferHandle,
}

/// Adds the path tracer at `width`×`height`, reading the scene and the frame constants.
pub fn add(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    frame: BufferHandle,
    spec: &Specialization,
    width: u32,
    height: u32,
) -> Outputs {
    let stats = crate::stats::add_counter(g, "path_trace.stats");
    let mut p = g.add_pass("path_trace");
    scene.read(&mut p);
    let frame = p.read(frame, Access::ComputeRead);
    let stats = p.write(stats, Access::ComputeReadWrite);
    let radiance = p.create_image("path_trace.radiance", ImageDesc::rgba32f(width, height));
    let radiance = p.write(radiance, Access::ComputeWrite);
    let demodulated = p.create_image("path_trace.demodulated", ImageDesc::rgba32f(width, height));
    let demodulated = p.write(demodulated, Access::ComputeWrite);
    let (scene, spec) = (*scene, spec.clone());
    p.execute(move |ctx| {
        let dispatch = ctx
            .compute(&PATH_TRACE)
            .specialization(&spec)
            .buffer("b_frame", frame)
            .buffer("b_stats", stats)
            .image("u_radiance", radiance)
            .image("u_demodulated", demodulated);
        scene.bind(dispatch).dispatch_threads([width, height, 1])
    });
    Outputs {
        radiance,
        demodulated,
        stats,
    }
}
