//! The work layout of an a-trous step in shared memory (`shaders/common/atrous_tile.glsl`): SVGF's
//! iterations and the learned denoiser's gated filter dispatch by it.

/// Side of a workgroup, in invocations (`ATROUS_GROUP`).
const GROUP: u32 = 16;
/// The longest run of adjacent pixels a workgroup filters in x (`ATROUS_MAX_RUN`).
const MAX_RUN: u32 = 4;

/// The invocations of the iteration of `step` (a power of two) on a `width` x `height` image:
/// in x, `step / run` runs of residues times the tiles of 16 / `run` columns that cover a
/// residue's `ceil(width / step)` columns (`run` = min(step, 4)); in y, `step` residues times the
/// tiles of 16 rows that cover a residue's `ceil(height / step)` rows.
pub(crate) fn threads(step: u32, (width, height): (u32, u32)) -> [u32; 3] {
    let run = step.min(MAX_RUN);
    let tiles_x = width.div_ceil(step).div_ceil(GROUP / run);
    let tiles_y = height.div_ceil(step).div_ceil(GROUP);
    [step / run * tiles_x * GROUP, step * tiles_y * GROUP, 1]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pixel that invocation `(x, y)` filters, as `atrous_cell_pixel` maps it.
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
            for step in [1, 2, 4, 8, 16, 32, 64] {
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
