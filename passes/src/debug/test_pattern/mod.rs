//! A three-pass test pattern: a gradient image, the sum of each row, and their combination.
//! It exercises image and buffer barriers, push constants, a specialization constant and a
//! specialized workgroup size; tests know its exact output ([`expected`]).

use crate::shaders::test_pattern::{COMBINE, GRADIENT, ROW_SUM};
use bytemuck::{Pod, Zeroable};
use lucid_engine::graph::{BufferHandle, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// Parameters of the pattern.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Multiplies the gradient and checkerboard.
    pub gain: f32,
    /// Checkerboard cell size in pixels (at least 1).
    pub checker: u32,
    /// Added to RGB in the last pass (when `add_offset`).
    pub offset: f32,
    /// Specializes the last pass with or without the offset.
    pub add_offset: bool,
    /// Workgroup width of the last pass (a specialization constant).
    pub combine_group_width: u32,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            gain: 1.0,
            checker: 8,
            offset: 0.25,
            add_offset: true,
            combine_group_width: 8,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GradientPush {
    gain: f32,
    checker: u32,
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct CombinePush {
    offset: f32,
}

/// The pattern's resources.
#[derive(Clone, Copy, Debug)]
pub struct Outputs {
    /// The gradient and checkerboard.
    pub pattern: ImageHandle,
    /// One float per row: the sum of the pattern's red channel.
    pub row_sums: BufferHandle,
    /// The pattern plus offset in RGB, with its row's sum in alpha.
    pub combined: ImageHandle,
}

/// Adds the three passes to `g`.
pub fn add_test_pattern(g: &mut RenderGraph, width: u32, height: u32, params: &Params) -> Outputs {
    let gradient_push = GradientPush {
        gain: params.gain,
        checker: params.checker.max(1),
    };
    let mut pass = g.compute_pass("test_pattern.gradient", &GRADIENT);
    let pattern = pass.create_image(
        "u_out",
        "test_pattern.pattern",
        ImageDesc::rgba32f(width, height),
    );
    pass.push(&gradient_push);
    pass.dispatch([width, height, 1]);

    let mut pass = g.compute_pass("test_pattern.row_sum", &ROW_SUM);
    pass.read("u_in", pattern);
    let sums = pass.create_buffer("b_sums", "test_pattern.row_sums", 4 * height as u64);
    pass.dispatch([height, 1, 1]);

    let mut pass = g.compute_pass("test_pattern.combine", &COMBINE);
    pass.read("u_in", pattern).read("RowSums", sums);
    let combined = pass.create_image(
        "u_out",
        "test_pattern.combined",
        ImageDesc::rgba32f(width, height),
    );
    pass.specialize("ADD_OFFSET", params.add_offset)
        .specialize("local_size_x", params.combine_group_width.max(1))
        .push(&CombinePush {
            offset: params.offset,
        });
    pass.dispatch([width, height, 1]);
    Outputs {
        pattern,
        row_sums: sums,
        combined,
    }
}

/// The exact pattern pixel at (x, y), as the gradient pass computes it.
pub fn expected_pattern(width: u32, height: u32, x: u32, y: u32, params: &Params) -> [f32; 4] {
    let checker = params.checker.max(1);
    let check = (((x / checker) + (y / checker)) & 1) as f32;
    [
        x as f32 / width as f32 * params.gain,
        y as f32 / height as f32 * params.gain,
        check * params.gain,
        1.0,
    ]
}

/// The combined output, computed on the CPU the way the GPU does (row sums in index order).
pub fn expected(width: u32, height: u32, params: &Params) -> Vec<[f32; 4]> {
    let offset = if params.add_offset {
        params.offset
    } else {
        0.0
    };
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        let sum: f32 = (0..width)
            .map(|x| expected_pattern(width, height, x, y, params)[0])
            .sum();
        for x in 0..width {
            let p = expected_pattern(width, height, x, y, params);
            out.push([p[0] + offset, p[1] + offset, p[2] + offset, sum]);
        }
    }
    out
}
