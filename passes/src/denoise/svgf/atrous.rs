//! The a-trous iterations of SVGF's filter (`shaders/svgf/{atrous,atrous_feedback}.comp`, in
//! `shaders/svgf/atrous.glsl`, on the tile of `shaders/common/atrous_tile.glsl`).
//!
//! Each iteration's workgroup filters 16x16 pixels a step apart (in x, runs of up to 4 adjacent
//! pixels a step apart) and first reads the tile their 5x5 taps cover into shared memory: per
//! pixel, 1.6 to 2.5 texels of each of the illumination, depth and normal images, and 5 fetches
//! of its own (the depth slope, four gathers of the 3x3 standard deviations the luminance scale
//! blurs), about 10 in all where taps reading the images would take 87.

use super::SvgfParams;
use crate::denoise::atrous_tile::threads;
use crate::denoise::gbuffer::GBuffer;
use crate::shaders::svgf::{ATROUS, ATROUS_FEEDBACK};
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// Push constants of the a-trous shaders.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct AtrousParams {
    step: i32,
    sigma_z: f32,
    sigma_n: f32,
    sigma_l: f32,
}

/// Adds `params.iterations` a-trous iterations (steps 1, 2, 4, ...) on `input` (illumination and
/// standard deviation, `svgf_pack_filtered`), with the depth slope `depth_slope` of
/// `svgf/variance.comp`. The first iteration's output is also written to `feedback` (the colour
/// history) when given. Returns the last iteration's output.
pub(super) fn add(
    g: &mut RenderGraph,
    (input, depth_slope): (ImageHandle, ImageHandle),
    gbuffer: &GBuffer,
    params: &SvgfParams,
    feedback: Option<ImageHandle>,
    (width, height): (u32, u32),
) -> ImageHandle {
    let desc = ImageDesc::rgba16f(width, height);
    let mut filtered = input;
    for i in 0..params.iterations {
        let history = feedback.filter(|_| i == 0);
        let shader = if history.is_some() {
            &ATROUS_FEEDBACK
        } else {
            &ATROUS
        };
        let step = 1 << i;
        let mut pass = g.compute_pass("svgf.atrous", shader);
        pass.sample("u_in", filtered)
            .read("u_depth", gbuffer.depth)
            .read("u_normal_roughness", gbuffer.normal_roughness)
            .read("u_depth_slope", depth_slope);
        let out = pass.create_image("u_out", "svgf.atrous", desc);
        if let Some(history) = history {
            pass.write("u_history", history);
        }
        pass.push(&AtrousParams {
            step: step as i32,
            sigma_z: params.sigma_z,
            sigma_n: params.sigma_n,
            sigma_l: params.sigma_l,
        });
        pass.dispatch(threads(step, (width, height)));
        filtered = out;
    }
    filtered
}
