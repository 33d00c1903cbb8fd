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
//! The histories are the render graph's keyed temporal images ([`COLOR_KEY`], [`MOMENTS_KEY`],
//! [`SURFACE_KEY`], [`ALBEDO_KEY`], [`EMISSION_KEY`]): a resize or
//! [`Executor::reset_history`](lucid_engine::graph::Executor::reset_history) starts them afresh.
//! The spatial modes filter the (accumulated) output, demodulated by the first hits' albedo and
//! emission accumulated over the same frames (`demodulate`).

mod demodulate;
mod filter;
mod gradient;
mod params;
mod schedule;
mod temporal;

pub use demodulate::{ALBEDO_ACCUMULATED_KEY, EMISSION_ACCUMULATED_KEY};
pub use params::{SvgfMode, SvgfParams};
pub use schedule::{Apply, Schedule};

use crate::denoise::gbuffer::GBuffer;
use crate::light_transport::{self, ReplayParams};
use lucid_engine::graph::{ImageHandle, RenderGraph, TemporalImage};

/// History key of the filtered illumination (output of the first a-trous iteration).
pub const COLOR_KEY: &str = "svgf.color";
/// History key of the luminance moments and history length.
pub const MOMENTS_KEY: &str = "svgf.moments";
/// History key of the surface records (depth, normal, object id, raw radiance luminance).
pub const SURFACE_KEY: &str = "svgf.surface";
/// History key of the averaged first-hit albedo.
pub const ALBEDO_KEY: &str = "svgf.albedo";
/// History key of the averaged first-hit emission.
pub const EMISSION_KEY: &str = "svgf.emission";

/// The keyed histories of one frame.
struct Histories {
    color: TemporalImage,
    moments: TemporalImage,
    surface: TemporalImage,
    albedo: TemporalImage,
    emission: TemporalImage,
}

/// What the denoiser reads of a frame.
pub struct FrameInputs {
    /// This frame's noisy radiance.
    pub radiance: ImageHandle,
    /// The light transport's images for denoisers (the temporal filter's input).
    pub surface: light_transport::SurfaceImages,
    /// The (accumulated) output the spatial modes filter.
    pub accumulated: ImageHandle,
    /// Frames averaged into `accumulated` before this one (0: it is this frame's radiance).
    pub accumulated_frames: u32,
    /// What the light transport replayed this frame for the temporal gradients (see [`replay`];
    /// stratum 0 when nothing, e.g. an algorithm that cannot replay paths).
    pub replay: ReplayParams,
    /// This frame's index (the replayed pixels depend on it).
    pub frame_index: u32,
    /// Primary visibility.
    pub gbuffer: GBuffer,
    /// Output width.
    pub width: u32,
    /// Output height.
    pub height: u32,
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

/// What the denoiser adds to a frame.
#[derive(Clone, Copy, Debug)]
pub struct Denoised {
    /// The denoised radiance (`inputs.accumulated` when nothing was applied).
    pub image: ImageHandle,
    /// The temporal filter's gradients, one texel per stratum of
    /// [`SvgfParams::gradient_stratum`] pixels, spread over their neighbourhood: x the luminance
    /// change since last frame, y its normaliser (x / y is the share of history dropped). `None`
    /// unless the temporal filter ran.
    pub gradient: Option<ImageHandle>,
}

/// Adds what `apply` asks for. The spatial modes average the first hits' albedo and emission
/// every frame, filtered or not, so that they match the accumulated radiance once the filter
/// starts.
pub fn add_svgf(
    g: &mut RenderGraph,
    inputs: &FrameInputs,
    params: &SvgfParams,
    apply: Apply,
) -> Denoised {
    let spatial = |image| Denoised {
        image,
        gradient: None,
    };
    match apply {
        Apply::Temporal { continues } => add_svgf_temporal(g, inputs, params, continues),
        Apply::Spatial => {
            let surface = demodulate::accumulate_surface(g, inputs);
            spatial(add_spatial(g, inputs, params, surface))
        }
        Apply::Nothing => {
            if params.mode != SvgfMode::Temporal {
                demodulate::accumulate_surface(g, inputs);
            }
            spatial(inputs.accumulated)
        }
    }
}

/// Adds full SVGF on `inputs.radiance`; `continues`: the histories hold last frame (else they are
/// ignored, as after a reset).
pub fn add_svgf_temporal(
    g: &mut RenderGraph,
    inputs: &FrameInputs,
    params: &SvgfParams,
    continues: bool,
) -> Denoised {
    let params = SvgfParams {
        iterations: params.iterations.max(1),
        gradient_stratum: params.gradient_stratum.max(1),
        ..*params
    };
    let size = (inputs.width, inputs.height);
    let (color_desc, surface_desc) = temporal::history_descs(inputs.width, inputs.height);
    let history = Histories {
        color: g.temporal_image(COLOR_KEY, color_desc),
        moments: g.temporal_image(MOMENTS_KEY, color_desc),
        surface: g.temporal_image(SURFACE_KEY, surface_desc),
        albedo: g.temporal_image(ALBEDO_KEY, color_desc),
        emission: g.temporal_image(EMISSION_KEY, color_desc),
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
    }
}

/// Adds the spatial filter alone (variance estimated spatially) on `inputs.accumulated`,
/// demodulated by `surface`, the first hits' albedo and emission accumulated over the same frames
/// (see [`demodulate::accumulate_surface`]).
fn add_spatial(
    g: &mut RenderGraph,
    inputs: &FrameInputs,
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
