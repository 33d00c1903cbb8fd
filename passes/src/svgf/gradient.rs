//! A-SVGF temporal gradients (`shaders/svgf/gradient.comp`, `gradient_filter.comp`): re-traced
//! samples per stratum compared with last frame's radiance, then spread over a neighbourhood.

use crate::scene_buffers::SceneHandles;
use crate::shaders::svgf::{GRADIENT, GRADIENT_FILTER};
use lucid_engine::graph::{Access, BufferHandle, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::Specialization;

/// A-trous iterations over the stratum gradients (3x3 boxes 1 and 2 strata apart: a 7x7-stratum
/// footprint).
const FILTER_ITERATIONS: u32 = 2;

/// What the gradient passes read.
pub(super) struct GradientInputs<'a> {
    pub scene: &'a SceneHandles,
    pub frame: BufferHandle,
    pub spec: &'a Specialization,
    pub motion: ImageHandle,
    pub prev_surface: ImageHandle,
    pub enabled: bool,
    /// Side of a stratum in pixels, at least 1.
    pub stratum: u32,
    pub width: u32,
    pub height: u32,
}

/// Adds the gradient passes; returns per stratum (filtered luminance difference, normaliser).
pub(super) fn add(g: &mut RenderGraph, inputs: &GradientInputs<'_>) -> ImageHandle {
    let stratum = inputs.stratum;
    let (gw, gh) = (
        inputs.width.div_ceil(stratum),
        inputs.height.div_ceil(stratum),
    );
    let mut p = g.add_pass("svgf.gradient");
    inputs.scene.read(&mut p);
    let frame = p.read(inputs.frame, Access::ComputeRead);
    let motion = p.read(inputs.motion, Access::ComputeRead);
    let prev_surface = p.read(inputs.prev_surface, Access::ComputeRead);
    let out = p.create_image("svgf.gradient", ImageDesc::rgba32f(gw, gh));
    let out = p.write(out, Access::ComputeWrite);
    let (scene, spec) = (*inputs.scene, inputs.spec.clone());
    let push = [u32::from(inputs.enabled), stratum];
    p.execute(move |ctx| {
        let enabled = if ctx.history_valid(prev_surface) {
            push
        } else {
            [0, stratum]
        };
        let dispatch = ctx
            .compute(&GRADIENT)
            .specialization(&spec)
            .buffer("b_frame", frame)
            .image("u_motion", motion)
            .image("u_prev_surface", prev_surface)
            .image("u_gradient", out)
            .push(&enabled);
        scene.bind(dispatch).dispatch_threads([gw, gh, 1])
    });
    (0..FILTER_ITERATIONS).fold(out, |input, i| {
        let mut p = g.add_pass("svgf.gradient_filter");
        let input = p.read(input, Access::ComputeRead);
        let out = p.create_image("svgf.gradient_filtered", ImageDesc::rgba32f(gw, gh));
        let out = p.write(out, Access::ComputeWrite);
        let step = 1i32 << i;
        p.execute(move |ctx| {
            ctx.compute(&GRADIENT_FILTER)
                .image("u_in", input)
                .image("u_out", out)
                .push(&step)
                .dispatch_threads([gw, gh, 1])
        });
        out
    })
}
