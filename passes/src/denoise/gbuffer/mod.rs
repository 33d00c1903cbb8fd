//! The G-buffer: primary visibility at pixel centres (`shaders/gbuffer/gbuffer.comp`), for
//! denoisers and debug views.

use crate::plumbing::scene_buffers::SceneHandles;
use crate::shaders::gbuffer::GBUFFER;
use ash::vk;
use lucid_engine::graph::{BufferHandle, ImageHandle, RenderGraph};
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
pub fn add_gbuffer(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    frame: BufferHandle,
    prev_transforms: BufferHandle,
    spec: &Specialization,
    width: u32,
    height: u32,
) -> GBuffer {
    let mut pass = g.compute_pass("gbuffer", &GBUFFER);
    scene.read(&mut pass);
    pass.specialization(spec)
        .read("b_frame", frame)
        .read("b_prev_transforms", prev_transforms);
    // The image `gbuffer.<name>`, bound as `u_<name>`.
    let mut image = |name: &str, format: vk::Format| {
        let desc = ImageDesc::new(width, height, format);
        pass.create_image(&format!("u_{name}"), &format!("gbuffer.{name}"), desc)
    };
    let out = GBuffer {
        depth: image("depth", vk::Format::R32_SFLOAT),
        normal_roughness: image("normal_roughness", vk::Format::R16G16B16A16_SFLOAT),
        albedo: image("albedo", vk::Format::R16G16B16A16_SFLOAT),
        emission: image("emission", vk::Format::R16G16B16A16_SFLOAT),
        ids: image("ids", vk::Format::R32G32B32A32_UINT),
        motion: image("motion", vk::Format::R16G16B16A16_SFLOAT),
    };
    pass.dispatch([width, height, 1]);
    out
}
