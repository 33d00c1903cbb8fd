//! The emission seen directly, supersampled at emitters' edges
//! (`shaders/edge_emission/edge_emission.comp`): what the denoisers add back to their output.
//!
//! With one sample a pixel, a pixel on an emitter's edge sees the emitter or what is beside it, so
//! the emission a denoiser re-modulates with jumps from frame to frame (the lights of `classroom`
//! carried about half of both denoisers' temporal instability). There, and only there, a grid of
//! camera rays measures the pixel's coverage; every other pixel keeps the light transport's
//! average, so a scene pays for the pixels on its emitters' edges only.

use crate::denoise::gbuffer::GBuffer;
use crate::light_transport::SurfaceImages;
use crate::plumbing::scene_buffers::SceneHandles;
use crate::shaders::edge_emission::EDGE_EMISSION;
use ash::vk;
use lucid_engine::graph::{BufferHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::Specialization;

/// Adds the pass: `surface` with its emission supersampled where the G-buffer finds an emitter's
/// (or the sky's) edge, the rest as traced.
pub fn add_edge_emission(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    frame: BufferHandle,
    (gbuffer, surface): (&GBuffer, SurfaceImages),
    spec: &Specialization,
    (width, height): (u32, u32),
) -> SurfaceImages {
    let mut pass = g.compute_pass("edge_emission", &EDGE_EMISSION);
    scene.read(&mut pass);
    pass.specialization(spec)
        .read("b_frame", frame)
        .read("u_ids", gbuffer.ids)
        .read("u_centre_emission", gbuffer.emission)
        .read("u_traced_emission", surface.emission);
    let desc = ImageDesc::new(width, height, vk::Format::R32G32B32A32_SFLOAT);
    let emission = pass.create_image("u_emission", "edge_emission.emission", desc);
    pass.dispatch([width, height, 1]);
    SurfaceImages {
        emission,
        ..surface
    }
}
