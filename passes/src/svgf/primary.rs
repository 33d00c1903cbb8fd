//! Antialiased primary hits and the demodulated input (`shaders/svgf/primary.comp`).

use crate::scene_buffers::SceneHandles;
use crate::shaders::svgf::PRIMARY;
use lucid_engine::graph::{Access, BufferHandle, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::Specialization;

/// What the filter works on and re-modulates with.
#[derive(Clone, Copy, Debug)]
pub(super) struct Primary {
    /// The input's radiance without directly seen emission, divided by the albedo.
    pub illumination: ImageHandle,
    /// Antialiased albedo to re-modulate with.
    pub albedo: ImageHandle,
    /// Antialiased directly seen emission to add back.
    pub emission: ImageHandle,
}

/// Adds the primary-hit pass over `radiance` with `grid` x `grid` antialiasing rays per pixel.
/// `exact_sample`: `radiance` is this frame's single path-traced sample per pixel, whose own
/// primary hit is demodulated exactly.
pub(super) fn add(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    frame: BufferHandle,
    spec: &Specialization,
    radiance: ImageHandle,
    (exact_sample, grid): (bool, u32),
    (width, height): (u32, u32),
) -> Primary {
    let mut p = g.add_pass("svgf.primary");
    scene.read(&mut p);
    let frame = p.read(frame, Access::ComputeRead);
    let radiance = p.read(radiance, Access::ComputeRead);
    let mut image = |name: &str| {
        let h = p.create_image(name, ImageDesc::rgba32f(width, height));
        p.write(h, Access::ComputeWrite)
    };
    let out = Primary {
        illumination: image("svgf.illumination"),
        albedo: image("svgf.albedo"),
        emission: image("svgf.emission"),
    };
    let (scene, spec) = (*scene, spec.clone());
    let push = [u32::from(exact_sample), grid];
    p.execute(move |ctx| {
        let dispatch = ctx
            .compute(&PRIMARY)
            .specialization(&spec)
            .buffer("b_frame", frame)
            .image("u_radiance", radiance)
            .image("u_illumination", out.illumination)
            .image("u_albedo", out.albedo)
            .image("u_emission", out.emission)
            .push(&push);
        scene.bind(dispatch).dispatch_threads([width, height, 1])
    });
    out
}
