//! The demodulated input of the spatial filter and what it re-modulates with
//! (`shaders/svgf/demodulate.comp`).

use super::HistoryKeys;
use crate::denoise::accumulate;
use crate::denoise::DenoiseInputs;
use crate::shaders::svgf::DEMODULATE;
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// What the filter works on and re-modulates with.
#[derive(Clone, Copy, Debug)]
pub(super) struct Demodulated {
    /// Radiance without the directly seen emission, divided by the first-hit albedo.
    pub illumination: ImageHandle,
    /// The first-hit albedo to re-modulate with.
    pub albedo: ImageHandle,
    /// The directly seen emission to add back.
    pub emission: ImageHandle,
}

/// Averages the light transport's first-hit albedo and emission over the frames its radiance is
/// accumulated over (the spatial modes run every frame this, so that these means are ready when
/// the filter starts).
pub(super) fn accumulate_surface(
    g: &mut RenderGraph,
    inputs: &DenoiseInputs,
    keys: &HistoryKeys,
) -> (ImageHandle, ImageHandle) {
    let (w, h, n) = (inputs.width, inputs.height, inputs.accumulated_frames);
    let albedo = accumulate::add_accumulate_keyed(
        g,
        &keys.albedo_accumulated,
        inputs.surface.albedo,
        (w, h),
        n,
    );
    let emission = accumulate::add_accumulate_keyed(
        g,
        &keys.emission_accumulated,
        inputs.surface.emission,
        (w, h),
        n,
    );
    (albedo, emission)
}

/// The spatial filter's input: this frame's exactly demodulated radiance when nothing was
/// accumulated yet, else the accumulated radiance demodulated by the accumulated `surface`
/// (albedo, emission).
pub(super) fn add(
    g: &mut RenderGraph,
    inputs: &DenoiseInputs,
    (albedo, emission): (ImageHandle, ImageHandle),
) -> Demodulated {
    if inputs.accumulated_frames == 0 {
        return Demodulated {
            illumination: inputs.surface.demodulated,
            albedo: inputs.surface.albedo,
            emission: inputs.surface.emission,
        };
    }
    let (width, height) = (inputs.width, inputs.height);
    let mut pass = g.compute_pass("svgf.demodulate", &DEMODULATE);
    pass.read("u_radiance", inputs.accumulated)
        .read("u_albedo", albedo)
        .read("u_emission", emission);
    let illumination = pass.create_image(
        "u_illumination",
        "svgf.illumination",
        ImageDesc::rgba32f(width, height),
    );
    pass.dispatch([width, height, 1]);
    Demodulated {
        illumination,
        albedo,
        emission,
    }
}
