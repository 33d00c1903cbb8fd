//! Spatiotemporal variance-guided filtering (Schied et al. 2017) with A-SVGF's temporal gradients
//! (Schied et al. 2018), in compute passes over the G-buffer (`shaders/svgf/`).
//!
//! Temporal mode, per frame:
//! 1. **Gradients** (`gradient`): on frames after the scene changed (every frame with
//!    [`SvgfParams::gradients_every_frame`]), the light transport replays, at one pixel per stratum
//!    of n x n pixels ([`SvgfParams::gradient_stratum`]), the path last frame's pixel it came from
//!    traced, with last frame's camera and random numbers ([`replay`] decides,
//!    `shaders/common/replay.glsl` picks the pixels); the difference from what that path gave last
//!    frame is spread over 7x7 strata. Where only the camera moved it is exactly zero (hence not
//!    replayed then); where a light or an object changed it measures the share of shading that
//!    changed. The replay costs no extra paths: the picked pixel's sample is the replayed one.
//! 2. **Temporal accumulation** (`temporal`): the light-transport pass demodulated each sample by
//!    its own first hit, `(radiance - emission) / albedo` ([`light_transport::SurfaceImages`]); reproject the
//!    history with the motion vectors (bilinear taps validated by depth, normal and object id,
//!    else a 3x3 search, else a disocclusion), blend this illumination, the first two luminance
//!    moments and the first hits' albedo and emission with moving averages whose weight the
//!    gradient raises, count the history length. The averaged albedo and emission are antialiased
//!    (each frame's samples are jittered over the pixel), so emitter and texture edges do not
//!    flicker under sub-pixel motion.
//! 3. **Filter** (`filter`): variance from the moments (spatial 7x7 estimate while the history
//!    is shorter than 4 frames), `iterations` a-trous iterations with depth, normal and
//!    luminance-variance edge stopping; the first iteration's output is the next frame's colour
//!    history; re-modulation by albedo plus emission.
//!
//! The histories are the render graph's keyed temporal images, named under each instance's
//! prefix ([`HistoryKeys`]): a resize or
//! [`Executor::reset_history`](lucid_engine::graph::Executor::reset_history) starts them afresh.
//! The spatial modes filter the (accumulated) output, demodulated by the first hits' albedo and
//! emission accumulated over the same frames (`demodulate`).
//!
//! With a still camera and accumulation on, the temporal mode's image hands over to the
//! accumulated one per pixel after [`Handoff::SVGF`]'s frames (`crate::denoise::handoff`), so it
//! keeps converging where SVGF's moving averages stop.

mod atrous;
mod demodulate;
mod filter;
mod gradient;
mod params;
mod schedule;
mod temporal;

pub use params::{SvgfMode, SvgfParams};
pub use schedule::{Apply, Schedule};

use crate::denoise::handoff::{self, Handoff};
use crate::denoise::{DenoiseInputs, Denoised, FrameDenoiser, FrameInfo, TransportRequest};
use crate::light_transport::ReplayParams;
use lucid_engine::graph::{ImageHandle, RenderGraph, TemporalImage};

/// The history keys of one SVGF instance, all under its prefix (`<prefix>.color`, ...).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HistoryKeys {
    /// The filtered illumination (output of the first a-trous iteration).
    pub color: String,
    /// The luminance moments and history length.
    pub moments: String,
    /// The surface records (depth, normal, object id, raw radiance luminance).
    pub surface: String,
    /// The averaged first-hit albedo.
    pub albedo: String,
    /// The averaged first-hit emission.
    pub emission: String,
    /// The first-hit albedo accumulated with the radiance (spatial modes).
    pub albedo_accumulated: String,
    /// The first-hit emission accumulated with the radiance (spatial modes).
    pub emission_accumulated: String,
}

impl HistoryKeys {
    /// The keys under `prefix`.
    pub fn new(prefix: &str) -> Self {
        let key = |name: &str| format!("{prefix}.{name}");
        Self {
            color: key("color"),
            moments: key("moments"),
            surface: key("surface"),
            albedo: key("albedo"),
            emission: key("emission"),
            albedo_accumulated: key("albedo.accumulated"),
            emission_accumulated: key("emission.accumulated"),
        }
    }
}

/// The keyed histories of one frame.
struct Histories {
    color: TemporalImage,
    moments: TemporalImage,
    surface: TemporalImage,
    albedo: TemporalImage,
    emission: TemporalImage,
}

/// SVGF as the renderer's denoiser: its parameters, its schedule (when the spatial modes start)
/// and its histories.
#[derive(Clone, Debug)]
pub struct SvgfDenoiser {
    params: SvgfParams,
    schedule: Schedule,
    keys: HistoryKeys,
    prefix: String,
    apply: Apply,
}

impl SvgfDenoiser {
    /// SVGF with `params`, its histories under `prefix`.
    pub fn new(params: SvgfParams, prefix: &str) -> Self {
        Self {
            params,
            schedule: Schedule::default(),
            keys: HistoryKeys::new(prefix),
            prefix: prefix.to_owned(),
            apply: Apply::Nothing,
        }
    }

    /// Changes the parameters from the next frame on (the schedule and histories carry on).
    pub fn set_params(&mut self, params: SvgfParams) {
        self.params = params;
    }
}

impl FrameDenoiser for SvgfDenoiser {
    fn plan(&mut self, frame: &FrameInfo) -> Option<TransportRequest> {
        self.apply = self.schedule.decide(
            self.params.mode,
            frame.frame_index,
            frame.accumulated_frames,
            frame.samples_per_pixel,
        );
        let replay_stratum = if frame.replays_paths {
            replay(&self.params, self.apply, frame.scene_changed)
        } else {
            0
        };
        Some(TransportRequest { replay_stratum })
    }

    fn add(&mut self, g: &mut RenderGraph, inputs: &DenoiseInputs) -> Denoised {
        let denoised = add_svgf(g, inputs, &self.params, self.apply, &self.keys);
        if !matches!(self.apply, Apply::Temporal { .. }) {
            return denoised;
        }
        Denoised {
            image: handoff::add_handoff(g, inputs, denoised.image, &self.prefix, Handoff::SVGF),
            ..denoised
        }
    }

    fn reset_on_scene_change(&self) -> Vec<String> {
        vec![handoff::history_key(&self.prefix)]
    }
}

/// The stratum side at which the light transport should replay last frame's paths this frame for
/// SVGF's temporal gradients (0: none): when `apply` continues the temporal filter with gradients
/// on, and shading can have changed where the camera alone did not move it (`scene_changed`: the
/// scene or the light transport's settings changed since last frame), or always with
/// [`SvgfParams::gradients_every_frame`].
pub fn replay(params: &SvgfParams, apply: Apply, scene_changed: bool) -> u32 {
    let continues = matches!(apply, Apply::Temporal { continues: true });
    if continues && params.gradients && (scene_changed || params.gradients_every_frame) {
        params.gradient_stratum.max(1)
    } else {
        0
    }
}

/// Adds what `apply` asks for, with the histories under `keys`. The spatial modes average the
/// first hits' albedo and emission every frame, filtered or not, so that they match the
/// accumulated radiance once the filter starts. The result's gradient (temporal mode only) holds
/// one texel per stratum of [`SvgfParams::gradient_stratum`] pixels, spread over their
/// neighbourhood: x the luminance change since last frame, y its normaliser (x / y is the share
/// of history dropped).
pub fn add_svgf(
    g: &mut RenderGraph,
    inputs: &DenoiseInputs,
    params: &SvgfParams,
    apply: Apply,
    keys: &HistoryKeys,
) -> Denoised {
    match apply {
        Apply::Temporal { continues } => add_svgf_temporal(g, inputs, params, continues, keys),
        Apply::Spatial => {
            let surface = demodulate::accumulate_surface(g, inputs, keys);
            Denoised::image(add_spatial(g, inputs, params, surface))
        }
        Apply::Nothing => {
            if params.mode != SvgfMode::Temporal {
                demodulate::accumulate_surface(g, inputs, keys);
            }
            Denoised::image(inputs.accumulated)
        }
    }
}

/// Adds full SVGF on `inputs.radiance`; `continues`: the histories hold last frame (else they are
/// ignored, as after a reset).
pub fn add_svgf_temporal(
    g: &mut RenderGraph,
    inputs: &DenoiseInputs,
    params: &SvgfParams,
    continues: bool,
    keys: &HistoryKeys,
) -> Denoised {
    let params = SvgfParams {
        iterations: params.iterations.max(1),
        gradient_stratum: params.gradient_stratum.max(1),
        firefly_headroom: params.firefly_headroom.max(1.0),
        ..*params
    };
    let size = (inputs.width, inputs.height);
    let (color_desc, surface_desc) = temporal::history_descs(inputs.width, inputs.height);
    let history = Histories {
        color: g.temporal_image(&keys.color, color_desc),
        moments: g.temporal_image(&keys.moments, color_desc),
        surface: g.temporal_image(&keys.surface, surface_desc),
        albedo: g.temporal_image(&keys.albedo, color_desc),
        emission: g.temporal_image(&keys.emission, color_desc),
    };
    let gradient = gradient::add(
        g,
        &gradient::GradientInputs {
            radiance: inputs.radiance,
            motion: inputs.gbuffer.motion,
            prev_surface: history.surface.prev,
            replay: if continues && inputs.replay.stratum == params.gradient_stratum {
                inputs.replay
            } else {
                ReplayParams::default()
            },
            frame_index: inputs.frame_index,
            stratum: params.gradient_stratum,
            width: inputs.width,
            height: inputs.height,
        },
    );
    let integrated = temporal::add(
        g,
        (inputs.radiance, &inputs.surface),
        &inputs.gbuffer,
        gradient,
        (&history, continues),
        &params,
        size,
    );
    let image = filter::add(
        g,
        (&integrated.demodulated, integrated.moments),
        &inputs.gbuffer,
        &params,
        Some(history.color.cur),
        size,
    );
    Denoised {
        image,
        gradient: Some(gradient),
        record: None,
    }
}

/// Adds the spatial filter alone (variance estimated spatially) on `inputs.accumulated`,
/// demodulated by `surface`, the first hits' albedo and emission accumulated over the same frames
/// (see [`demodulate::accumulate_surface`]).
fn add_spatial(
    g: &mut RenderGraph,
    inputs: &DenoiseInputs,
    params: &SvgfParams,
    surface: (ImageHandle, ImageHandle),
) -> ImageHandle {
    let size = (inputs.width, inputs.height);
    let demodulated = demodulate::add(g, inputs, surface);
    let moments = filter::moments(g, demodulated.illumination, size);
    filter::add(
        g,
        (&demodulated, moments),
        &inputs.gbuffer,
        params,
        None,
        size,
    )
}
