//! The learned denoiser's half-precision packing (`pack_channels` in `shaders/neural/tensor.glsl`)
//! over a buffer of floats, and the round trip through it that rounds values to half precision in
//! place (`shaders/half_pack/half_pack.comp`). Its test checks that the device rounds both as
//! training does (to nearest, ties to even): the denoiser's activations and its output's history,
//! fed back frame after frame, are rounded by them.

use crate::shaders::half_pack::HALF_PACK;
use lucid_engine::graph::{BufferHandle, RenderGraph};

/// What [`add_half_pack`] writes.
pub struct HalfPack {
    /// `count` uvec2s, four halves each (`packHalf2x16` layout: x's half in the low 16 bits).
    pub packed: BufferHandle,
    /// `count` vec4s: the values rounded to half precision by packing and unpacking them.
    pub rounded: BufferHandle,
}

/// Adds a pass packing `count` vec4s of `values` (std430) into four halves each, and rounding them
/// to half precision through the packing.
pub fn add_half_pack(g: &mut RenderGraph, values: BufferHandle, count: u32) -> HalfPack {
    let mut pass = g.compute_pass("half_pack", &HALF_PACK);
    pass.read("b_values", values);
    let packed = pass.create_buffer("b_packed", "half_pack.packed", count.max(1) as u64 * 8);
    let rounded = pass.create_buffer("b_rounded", "half_pack.rounded", count.max(1) as u64 * 16);
    pass.push(&count);
    pass.dispatch([count, 1, 1]);
    HalfPack { packed, rounded }
}
