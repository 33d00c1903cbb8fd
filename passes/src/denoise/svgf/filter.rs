//! SVGF's spatial half: variance estimation, the edge-avoiding a-trous wavelet filter
//! ([`atrous`]) and re-modulation (`shaders/svgf/{moments,variance,modulate}.comp`).

use super::atrous;
use super::demodulate::Demodulated;
use super::SvgfParams;
use crate::denoise::gbuffer::GBuffer;
use crate::shaders::svgf::{MODULATE, MOMENTS, VARIANCE};
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// Luminance moments of `illumination` with no history: the spatial-only filter's moments.
pub(super) fn moments(
    g: &mut RenderGraph,
    illumination: ImageHandle,
    (width, height): (u32, u32),
) -> ImageHandle {
    let mut pass = g.compute_pass("svgf.moments", &MOMENTS);
    pass.read("u_illumination", illumination);
    let moments = pass.create_image(
        "u_moments",
        "svgf.moments",
        ImageDesc::rgba32f(width, height),
    );
    pass.dispatch([width, height, 1]);
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
    // Half precision for the filter chain (svgf_pack_filtered): the iterations read half the bytes.
    let mut pass = g.compute_pass("svgf.variance", &VARIANCE);
    pass.read("u_color", demodulated.illumination)
        .read("u_moments", moments)
        .read("u_depth", gbuffer.depth)
        .read("u_normal_roughness", gbuffer.normal_roughness);
    let variance = pass.create_image("u_out", "svgf.variance", ImageDesc::rgba16f(width, height));
    let depth_slope = pass.create_image(
        "u_depth_slope",
        "svgf.depth_slope",
        ImageDesc::r32f(width, height),
    );
    pass.push(&[params.sigma_z, params.sigma_n]);
    pass.dispatch([width, height, 1]);
    let filtered = atrous::add(
        g,
        (variance, depth_slope),
        gbuffer,
        params,
        feedback,
        (width, height),
    );
    modulate(g, filtered, demodulated, (width, height))
}

/// Re-modulates filtered illumination by the albedo and adds the directly seen emission back.
fn modulate(
    g: &mut RenderGraph,
    illumination: ImageHandle,
    demodulated: &Demodulated,
    (width, height): (u32, u32),
) -> ImageHandle {
    let mut pass = g.compute_pass("svgf.modulate", &MODULATE);
    pass.read("u_illumination", illumination)
        .read("u_albedo", demodulated.albedo)
        .read("u_emission", demodulated.emission);
    let out = pass.create_image("u_out", "svgf.output", ImageDesc::rgba32f(width, height));
    pass.dispatch([width, height, 1]);
    out
}
