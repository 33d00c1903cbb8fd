//! SVGF temporal accumulation (`shaders/svgf/temporal.comp`) over the keyed histories.

use super::demodulate::Demodulated;
use super::{Histories, SvgfParams};
use crate::gbuffer::GBuffer;
use crate::shaders::svgf::TEMPORAL;
use crate::transport;
use lucid_engine::graph::{Access, ImageHandle, RenderGraph};
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
    pad: [f32; 2],
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
    (radiance, surface): (ImageHandle, &transport::SurfaceImages),
    gbuffer: &GBuffer,
    gradient: ImageHandle,
    (history, continues): (&Histories, bool),
    params: &SvgfParams,
    (width, height): (u32, u32),
) -> Integrated {
    let mut p = g.add_pass("svgf.temporal");
    let radiance = p.read(radiance, Access::ComputeRead);
    let illumination = p.read(surface.demodulated, Access::ComputeRead);
    let albedo = p.read(surface.albedo, Access::ComputeRead);
    let emission = p.read(surface.emission, Access::ComputeRead);
    let depth = p.read(gbuffer.depth, Access::ComputeRead);
    let normal = p.read(gbuffer.normal_roughness, Access::ComputeRead);
    let ids = p.read(gbuffer.ids, Access::ComputeRead);
    let motion = p.read(gbuffer.motion, Access::ComputeRead);
    let gradient = p.read(gradient, Access::ComputeRead);
    let prev_color = p.read(history.color.prev, Access::ComputeRead);
    let prev_moments = p.read(history.moments.prev, Access::ComputeRead);
    let prev_surface = p.read(history.surface.prev, Access::ComputeRead);
    let prev_albedo = p.read(history.albedo.prev, Access::ComputeRead);
    let prev_emission = p.read(history.emission.prev, Access::ComputeRead);
    let color = p.create_image("svgf.integrated", ImageDesc::rgba32f(width, height));
    let color = p.write(color, Access::ComputeWrite);
    let moments = p.write(history.moments.cur, Access::ComputeWrite);
    let surface = p.write(history.surface.cur, Access::ComputeWrite);
    let albedo_out = p.write(history.albedo.cur, Access::ComputeWrite);
    let emission_out = p.write(history.emission.cur, Access::ComputeWrite);
    let params = *params;
    p.execute(move |ctx| {
        let push = Params {
            alpha: params.alpha,
            moments_alpha: params.moments_alpha,
            history_valid: u32::from(continues && ctx.history_valid(prev_color)),
            stratum: params.gradient_stratum,
            max_history: MAX_HISTORY,
            surface_alpha: params.surface_alpha,
            pad: [0.0; 2],
        };
        ctx.compute(&TEMPORAL)
            .image("u_radiance", radiance)
            .image("u_illumination", illumination)
            .image("u_depth", depth)
            .image("u_normal_roughness", normal)
            .image("u_ids", ids)
            .image("u_motion", motion)
            .image("u_gradient", gradient)
            .image("u_prev_color", prev_color)
            .image("u_prev_moments", prev_moments)
            .image("u_prev_surface", prev_surface)
            .image("u_color", color)
            .image("u_moments", moments)
            .image("u_surface", surface)
            .image("u_albedo", albedo)
            .image("u_emission", emission)
            .image("u_prev_albedo", prev_albedo)
            .image("u_prev_emission", prev_emission)
            .image("u_albedo_out", albedo_out)
            .image("u_emission_out", emission_out)
            .push(&push)
            .dispatch_threads([width, height, 1])
    });
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
