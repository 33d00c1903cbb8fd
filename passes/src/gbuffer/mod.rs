//! The G-buffer: primary visibility at pixel centres (`shaders/gbuffer/gbuffer.comp`), for
//! denoisers and debug views.

use crate::scene_buffers::SceneHandles;
use crate::shaders::gbuffer::GBUFFER;
use ash::vk;
use lucid_engine::graph::{Access, BufferHandle, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::Specialization;

/// The G-buffer images.
#[derive(Clone, Copy, Debug)]
pub struct GBuffer {
    /// View-space depth along the camera's forward axis (0 where the sky is seen), `r32f`.
    pub depth: ImageHandle,
    /// World normal facing the camera (xyz) and GGX alpha (w; 1 for diffuse), `rgba16f`.
    pub normal_roughness: ImageHandle,
    /// The albedo radiance is demodulated by (white for dielectrics and the sky), `rgba16f`.
    pub albedo: ImageHandle,
    /// Radiance emitted towards the camera (emitters and sky), `rgba16f`.
    pub emission: ImageHandle,
    /// Object id (scene instance or `0x8000_0000 | sphere`), material, primitive, hit flag, `rgba32ui`.
    pub ids: ImageHandle,
    /// Offset to last frame's pixel (xy) and last frame's depth of the point (z), `rgba16f`.
    pub motion: ImageHandle,
}

/// Adds the G-buffer pass. `prev_transforms` holds last frame's object-to-world rows
/// (3 × vec4 per scene instance).
pub fn add(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    frame: BufferHandle,
    prev_transforms: BufferHandle,
    spec: &Specialization,
    width: u32,
    height: u32,
) -> GBuffer {
    let mut p = g.add_pass("gbuffer");
    scene.read(&mut p);
    let frame = p.read(frame, Access::ComputeRead);
    let prev_transforms = p.read(prev_transforms, Access::ComputeRead);
    let mut image = |name: &str, format: vk::Format| {
        let h = p.create_image(name, ImageDesc::new(width, height, format));
        p.write(h, Access::ComputeWrite)
    };
    let out = GBuffer {
        depth: image("gbuffer.depth", vk::Format::R32_SFLOAT),
        normal_roughness: image("gbuffer.normal_roughness", vk::Format::R16G16B16A16_SFLOAT),
        albedo: image("gbuffer.albedo", vk::Format::R16G16B16A16_SFLOAT),
        emission: image("gbuffer.emission", vk::Format::R16G16B16A16_SFLOAT),
        ids: image("gbuffer.ids", vk::Format::R32G32B32A32_UINT),
        motion: image("gbuffer.motion", vk::Format::R16G16B16A16_SFLOAT),
    };
    let (scene, spec) = (*scene, spec.clone());
    p.execute(move |ctx| {
        let dispatch = ctx
            .compute(&GBUFFER)
            .specialization(&spec)
            .buffer("b_frame", frame)
            .buffer("b_prev_transforms", prev_transforms)
            .image("u_depth", out.depth)
            .image("u_normal_roughness", out.normal_roughness)
            .image("u_albedo", out.albedo)
            .image("u_emission", out.emission)
            .image("u_ids", out.ids)
            .image("u_motion", out.motion);
        scene.bind(dispatch).dispatch_threads([width, height, 1])
    });
    out
}
