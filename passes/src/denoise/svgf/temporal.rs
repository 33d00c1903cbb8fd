//! SVGF temporal accumulation (`shaders/svgf/temporal.comp`) over the keyed histories.

use super::demodulate::Demodulated;
use super::{Histories, SvgfParams};
use crate::denoise::gbuffer::GBuffer;
use crate::light_transport;
use crate::shaders::svgf::TEMPORAL;
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// Push constants of `temporal.comp`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    alpha: f32,
    moments_alpha: f32,
    history_valid: u32,
    stratum: u32,
    max_history: f32,
    surface_alpha: f32,
    firefly_headroom: f32,
    pad: f32,
}

/// Longest history a pixel counts (the moving averages' weights stop falling before this).
const MAX_HISTORY: f32 = 64.0;

/// The integrated illumination and moments of this frame.
pub(super) struct Integrated {
    /// Demodulated illumination (rgb), the first-hit albedo and emission to re-modulate with
    /// (also this frame's albedo and emission histories).
    pub demodulated: Demodulated,
    /// Luminance moments (xy) and history length (z); also this frame's moments history.
    pub moments: ImageHandle,
}

/// Adds the temporal accumulation of the light transport's demodulated radiance, first-hit albedo
/// and emission, reading last frame's histories (unless `continues` is false) and writing this
/// frame's moments, albedo, emission and surface records.
pub(super) fn add(
    g: &mut RenderGraph,
    (radiance, surface): (ImageHandle, &light_transport::SurfaceImages),
    gbuffer: &GBuffer,
    gradient: ImageHandle,
    (history, continues): (&Histories, bool),
    params: &SvgfParams,
    (width, height): (u32, u32),
) -> Integrated {
    let mut pass = g.compute_pass("svgf.temporal", &TEMPORAL);
    pass.read("u_radiance", radiance)
        .read("u_illumination", surface.demodulated)
        .read("u_albedo", surface.albedo)
        .read("u_emission", surface.emission)
        .read("u_depth", gbuffer.depth)
        .read("u_normal_roughness", gbuffer.normal_roughness)
        .read("u_ids", gbuffer.ids)
        .read("u_motion", gbuffer.motion)
        .read("u_gradient", gradient)
        .read("u_prev_color", history.color.prev)
        .read("u_prev_moments", history.moments.prev)
        .read("u_prev_surface", history.surface.prev)
        .read("u_prev_albedo", history.albedo.prev)
        .read("u_prev_emission", history.emission.prev);
    let color = pass.create_image(
        "u_color",
        "svgf.integrated",
        ImageDesc::rgba32f(width, height),
    );
    let moments = pass.write("u_moments", history.moments.cur);
    pass.write("u_surface", history.surface.cur);
    let albedo_out = pass.write("u_albedo_out", history.albedo.cur);
    let emission_out = pass.write("u_emission_out", history.emission.cur);
    let (params, prev_color) = (*params, history.color.prev);
    pass.push_with(move |ctx| Params {
        alpha: params.alpha,
        moments_alpha: params.moments_alpha,
        history_valid: u32::from(continues && ctx.history_valid(prev_color)),
        stratum: params.gradient_stratum,
        max_history: MAX_HISTORY,
        surface_alpha: params.surface_alpha,
        firefly_headroom: if params.firefly_clamp {
            params.firefly_headroom
        } else {
            0.0
        },
        pad: 0.0,
    });
    pass.dispatch([width, height, 1]);
    Integrated {
        demodulated: Demodulated {
            illumination: color,
            albedo: albedo_out,
            emission: emission_out,
        },
        moments,
    }
}

/// The history images' formats: colour, moments, albedo and emission `rgba32f`, surface records
/// `rgba32ui`.
pub(super) fn history_descs(width: u32, height: u32) -> (ImageDesc, ImageDesc) {
    (
        ImageDesc::rgba32f(width, height),
        ImageDesc::new(width, height, ash::vk::Format::R32G32B32A32_UINT),
    )
}
