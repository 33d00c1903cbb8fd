//! The a-trous iterations of SVGF's filter (`shaders/svgf/{atrous,atrous_feedback}.comp`, layout
//! in `shaders/svgf/atrous.glsl`).
//!
//! Each iteration's workgroup filters 16x16 pixels a step apart (in x, runs of up to 4 adjacent
//! pixels a step apart) and first reads the tile their 5x5 taps cover into shared memory: per
//! pixel, 1.6 to 2.5 texels of each of the illumination, depth and normal images, and 5 fetches
//! of its own (the depth slope, four gathers of the 3x3 standard deviations the luminance scale
//! blurs), about 10 in all where taps reading the images would take 87.

use super::SvgfParams;
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

/// Side of a workgroup, in invocations (`SVGF_ATROUS_GROUP`).
const GROUP: u32 = 16;
/// The longest run of adjacent pixels a workgroup filters in x (`SVGF_ATROUS_MAX_RUN`).
const MAX_RUN: u32 = 4;

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

/// The invocations of the iteration of `step` (a power of two) on a `width` x `height` image:
/// in x, `step / run` runs of residues times the tiles of 16 / `run` columns that cover a
/// residue's `ceil(width / step)` columns (`run` = min(step, 4)); in y, `step` residues times the
/// tiles of 16 rows that cover a residue's `ceil(height / step)` rows.
fn threads(step: u32, (width, height): (u32, u32)) -> [u32; 3] {
    let run = step.min(MAX_RUN);
    let tiles_x = width.div_ceil(step).div_ceil(GROUP / run);
    let tiles_y = height.div_ceil(step).div_ceil(GROUP);
    [step / run * tiles_x * GROUP, step * tiles_y * GROUP, 1]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pixel that invocation `(x, y)` filters, as `svgf_atrous_cell_pixel` maps it.
    fn pixel(step: u32, (x, y): (u32, u32)) -> (u32, u32) {
        let run = step.min(MAX_RUN);
        let (group, local) = ((x / GROUP, y / GROUP), (x % GROUP, y % GROUP));
        let runs = step / run;
        let residue = (group.0 % runs * run, group.1 % step);
        let first = (group.0 / runs * (GROUP / run), group.1 / step * GROUP);
        (
            residue.0 + local.0 % run + step * (first.0 + local.0 / run),
            residue.1 + step * (first.1 + local.1),
        )
    }

    #[test]
    fn every_pixel_is_filtered_once() {
        for (width, height) in [(64, 64), (67, 45), (1920, 1080), (5, 3)] {
            for step in [1, 2, 4, 8, 16, 32] {
                let [tx, ty, _] = threads(step, (width, height));
                let mut count = vec![0u32; (width * height) as usize];
                for y in 0..ty {
                    for x in 0..tx {
                        let (px, py) = pixel(step, (x, y));
                        if px < width && py < height {
                            count[(py * width + px) as usize] += 1;
                        }
                    }
                }
                assert!(
                    count.iter().all(|&c| c == 1),
                    "step {step} at {width}x{height}"
                );
            }
        }
    }
}
