//! The ways Lucid's shaders round to half precision, over a buffer of floats
//! (`shaders/half_rounding/half_rounding.comp`): the learned denoiser's packing (`pack_channels` in
//! `shaders/neural/tensor.glsl`), the round trip through it that rounds values in place, and
//! `round_to_half` (`shaders/common/half_round.glsl`) before an `rgba16f` image store, as SVGF
//! stores its a-trous steps. Its test checks that each rounds as training does (to nearest, ties to
//! even): the learned denoiser's history, fed back frame after frame, is rounded by the packing,
//! and a store's own conversion may truncate.

use crate::shaders::half_rounding::HALF_ROUNDING;
use lucid_engine::graph::{BufferHandle, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// The texels in a row of [`HalfRounding::stored`].
pub const IMAGE_WIDTH: u32 = 256;

/// What [`add_half_rounding`] writes.
pub struct HalfRounding {
    /// `count` uvec2s, four halves each (`packHalf2x16` layout: x's half in the low 16 bits).
    pub packed: BufferHandle,
    /// `count` vec4s: the values rounded to half precision by packing and unpacking them.
    pub rounded: BufferHandle,
    /// The values through `round_to_half` stored in an `rgba16f` image, [`IMAGE_WIDTH`] a row (the
    /// rest of the last row unwritten).
    pub stored: ImageHandle,
}

/// Adds a pass rounding `count` vec4s of `values` (std430) to half precision each way.
pub fn add_half_rounding(g: &mut RenderGraph, values: BufferHandle, count: u32) -> HalfRounding {
    let mut pass = g.compute_pass("half_rounding", &HALF_ROUNDING);
    pass.read("b_values", values);
    let packed = pass.create_buffer("b_packed", "half_rounding.packed", count.max(1) as u64 * 8);
    let rounded = pass.create_buffer(
        "b_rounded",
        "half_rounding.rounded",
        count.max(1) as u64 * 16,
    );
    let rows = count.max(1).div_ceil(IMAGE_WIDTH);
    let stored = pass.create_image(
        "u_stored",
        "half_rounding.stored",
        ImageDesc::rgba16f(IMAGE_WIDTH, rows),
    );
    pass.specialize("IMAGE_WIDTH", IMAGE_WIDTH).push(&count);
    pass.dispatch([count, 1, 1]);
    HalfRounding {
        packed,
        rounded,
        stored,
    }
}
