//! SVGF's spatial half: variance estimation, the edge-avoiding a-trous wavelet filter and
//! re-modulation (`shaders/svgf/{moments,variance,atrous,atrous_feedback,modulate}.comp`).

use super::demodulate::Demodulated;
use super::SvgfParams;
use crate::gbuffer::GBuffer;
use crate::shaders::svgf::{ATROUS, ATROUS_FEEDBACK, MODULATE, MOMENTS, VARIANCE};
use lucid_engine::graph::{Access, ImageHandle, RenderGraph};
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

/// Luminance moments of `illumination` with no history: the spatial-only filter's moments.
pub(super) fn moments(
    g: &mut RenderGraph,
    illumination: ImageHandle,
    (width, height): (u32, u32),
) -> ImageHandle {
    let mut p = g.add_pass("svgf.moments");
    let illumination = p.read(illumination, Access::ComputeRead);
    let moments = p.create_image("svgf.moments", ImageDesc::rgba32f(width, height));
    let moments = p.write(moments, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&MOMENTS)
            .image("u_illumination", illumination)
            .image("u_moments", moments)
            .dispatch_threads([width, height, 1])
    });
    moments
}

/// Estimates variance (temporally, or spatially where the history is short), filters with
/// `params.iterations` a-trous iterations and re-modulates with `demodulated`'s albedo and emission.
/// The first iteration's output is also written to `feedback` (the colour history) when given.
/// Returns the denoised radiance.
pub(super) fn add(
    g: &mut RenderGraph,
    (demodulated, moments): (&Demodulated, ImageHandle),
    gbuffer: &GBuffer,
    params: &SvgfParams,
    feedback: Option<ImageHandle>,
    (width, height): (u32, u32),
) -> ImageHandle {
    // Half precision for the filter chain (svgf_pack_filtered): the iterations are memory-bound.
    let desc = ImageDesc::rgba16f(width, height);
    let mut p = g.add_pass("svgf.variance");
    let color = p.read(demodulated.illumination, Access::ComputeRead);
    let moments = p.read(moments, Access::ComputeRead);
    let depth = p.read(gbuffer.depth, Access::ComputeRead);
    let normal = p.read(gbuffer.normal_roughness, Access::ComputeRead);
    let out = p.create_image("svgf.variance", desc);
    let out = p.write(out, Access::ComputeWrite);
    let sigmas = [params.sigma_z, params.sigma_n];
    p.execute(move |ctx| {
        ctx.compute(&VARIANCE)
            .image("u_color", color)
            .image("u_moments", moments)
            .image("u_depth", depth)
            .image("u_normal_roughness", normal)
            .image("u_out", out)
            .push(&sigmas)
            .dispatch_threads([width, height, 1])
    });
    let mut filtered = out;
    for i in 0..params.iterations {
        let mut p = g.add_pass("svgf.atrous");
        let input = p.read(filtered, Access::ComputeRead);
        let depth = p.read(gbuffer.depth, Access::ComputeRead);
        let normal = p.read(gbuffer.normal_roughness, Access::ComputeRead);
        let out = p.create_image("svgf.atrous", desc);
        let out = p.write(out, Access::ComputeWrite);
        let history = feedback
            .filter(|_| i == 0)
            .map(|h| p.write(h, Access::ComputeWrite));
        let push = AtrousParams {
            step: 1 << i,
            sigma_z: params.sigma_z,
            sigma_n: params.sigma_n,
            sigma_l: params.sigma_l,
        };
        p.execute(move |ctx| {
            let shader = if history.is_some() {
                &ATROUS_FEEDBACK
            } else {
                &ATROUS
            };
            let dispatch = ctx
                .compute(shader)
                .image("u_in", input)
                .image("u_depth", depth)
                .image("u_normal_roughness", normal)
                .image("u_out", out);
            match history {
                Some(h) => dispatch.image("u_history", h),
                None => dispatch,
            }
            .push(&push)
            .dispatch_threads([width, height, 1])
        });
        filtered = out;
    }
    modulate(g, filtered, demodulated, (width, height))
}

/// Re-modulates filtered illumination by the albedo and adds the directly seen emission back.
fn modulate(
    g: &mut RenderGraph,
    illumination: ImageHandle,
    demodulated: &Demodulated,
    (width, height): (u32, u32),
) -> ImageHandle {
    let mut p = g.add_pass("svgf.modulate");
    let illumination = p.read(illumination, Access::ComputeRead);
    let albedo = p.read(demodulated.albedo, Access::ComputeRead);
    let emission = p.read(demodulated.emission, Access::ComputeRead);
    let out = p.create_image("svgf.output", ImageDesc::rgba32f(width, height));
    let out = p.write(out, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&MODULATE)
            .image("u_illumination", illumination)
            .image("u_albedo", albedo)
            .image("u_emission", emission)
            .image("u_out", out)
            .dispatch_threads([width, height, 1])
    });
    out
}
