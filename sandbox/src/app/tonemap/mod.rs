//! The display transform as a graph pass: HDR in, 8-bit sRGB-encoded pixels out, in the byte
//! order of the image they are copied into.

use crate::settings::DisplaySettings;
use bytemuck::{Pod, Zeroable};
use lucid_engine::graph::{Access, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::ShaderSource;

/// The compiled `tonemap.comp` (built by the sandbox's build script).
static TONEMAP: ShaderSource = ShaderSource {
    name: "sandbox/tonemap",
    path: "sandbox/src/app/tonemap/tonemap.comp",
    spirv: include_bytes!(concat!(env!("OUT_DIR"), "/tonemap.spv")),
};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Push {
    exposure_scale: f32,
    curve: u32,
    swap_rb: u32,
}

/// Adds the tone-mapping pass reading `hdr`; returns an RGBA8 image of `extent` whose bytes are
/// in BGRA order when `bgra` is set.
pub fn add(
    graph: &mut RenderGraph,
    hdr: ImageHandle,
    extent: [u32; 2],
    display: &DisplaySettings,
    bgra: bool,
) -> ImageHandle {
    let push = Push {
        exposure_scale: display.exposure.exp2(),
        curve: display.tone_mapper.shader_index(),
        swap_rb: u32::from(bgra),
    };
    let [w, h] = extent;
    let mut p = graph.add_pass("sandbox.tonemap");
    let input = p.read(hdr, Access::ComputeSampled);
    let out = p.create_image("sandbox.display", ImageDesc::rgba8(w, h));
    let out = p.write(out, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&TONEMAP)
            .image("u_hdr", input)
            .image("u_out", out)
            .push(&push)
            .dispatch_threads([w, h, 1])
    });
    out
}
