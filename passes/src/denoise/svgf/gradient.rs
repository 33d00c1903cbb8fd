//! A-SVGF temporal gradients (`shaders/svgf/gradient.comp`, `gradient_filter.comp`): per stratum,
//! the light transport's replay of last frame's path compared with what that path gave last frame,
//! then spread over a neighbourhood.

use crate::light_transport::ReplayParams;
use crate::shaders::svgf::{GRADIENT, GRADIENT_FILTER};
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// A-trous iterations over the stratum gradients (3x3 boxes 1 and 2 strata apart: a 7x7-stratum
/// footprint).
const FILTER_ITERATIONS: u32 = 2;

/// Push constants of `gradient.comp`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Push {
    replay: ReplayParams,
    frame: u32,
}

/// What the gradient passes read.
pub(super) struct GradientInputs {
    /// This frame's noisy radiance, replayed at the picked pixels.
    pub radiance: ImageHandle,
    pub motion: ImageHandle,
    pub prev_surface: ImageHandle,
    /// What the light transport replayed this frame (stratum 0: nothing; the gradients are zero).
    pub replay: ReplayParams,
    /// This frame's index (the replay picks depend on it).
    pub frame_index: u32,
    /// Side of a stratum in pixels, at least 1 (the gradient image has one texel per stratum).
    pub stratum: u32,
    pub width: u32,
    pub height: u32,
}

/// Adds the gradient passes; returns per stratum (filtered luminance difference, normaliser). When
/// nothing was replayed this frame the gradients are zero, and so is their filtered image: the
/// filter passes are not added.
pub(super) fn add(g: &mut RenderGraph, inputs: &GradientInputs) -> ImageHandle {
    let stratum = inputs.stratum;
    let (gw, gh) = (
        inputs.width.div_ceil(stratum),
        inputs.height.div_ceil(stratum),
    );
    let mut pass = g.compute_pass("svgf.gradient", &GRADIENT);
    let prev_surface = inputs.prev_surface;
    pass.read("u_radiance", inputs.radiance)
        .read("u_motion", inputs.motion)
        .read("u_prev_surface", prev_surface);
    let out = pass.create_image("u_gradient", "svgf.gradient", ImageDesc::rgba32f(gw, gh));
    let push = Push {
        replay: inputs.replay,
        frame: inputs.frame_index,
    };
    pass.push_with(move |ctx| {
        if ctx.history_valid(prev_surface) {
            push
        } else {
            Push {
                replay: ReplayParams::default(),
                ..push
            }
        }
    });
    pass.dispatch([gw, gh, 1]);
    if inputs.replay.stratum == 0 {
        return out;
    }
    (0..FILTER_ITERATIONS).fold(out, |input, i| {
        let mut pass = g.compute_pass("svgf.gradient_filter", &GRADIENT_FILTER);
        pass.read("u_in", input);
        let out = pass.create_image(
            "u_out",
            "svgf.gradient_filtered",
            ImageDesc::rgba32f(gw, gh),
        );
        pass.push(&(1i32 << i));
        pass.dispatch([gw, gh, 1]);
        out
    })
}
