//! The still-camera hand-off from a denoiser's output to the accumulated image
//! (`shaders/handoff/`). A temporal denoiser's image stops improving once its histories are full,
//! while plain accumulation keeps converging; no single "worth K samples" weight fits every scene
//! and metric (`training/README.md`). So the mix is chosen per pixel: the pixel's variance of the
//! accumulated mean (from a running second moment of the frames' luminance, kept here beside the
//! accumulate pass's mean) against the denoised image's squared error (bias^2), estimated over a
//! 5x5 neighbourhood as the squared difference from the accumulation beyond a margin times its
//! variance. The accumulated image weighs bias^2 / (bias^2 + variance): it takes over where it has
//! converged and leaves the denoised value where it has not (fireflies, caustics). It fades in
//! after a number of still frames. How many, and how far above the noise a difference must be,
//! are each denoiser's ([`Handoff`]).

use crate::denoise::DenoiseInputs;
use crate::shaders::handoff::{BLEND, MOMENT};
use ash::vk;
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// When, and how readily, a denoiser's image is handed over to the accumulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Handoff {
    /// Accumulated frames before the hand-off starts; it fades in over as many more.
    pub first_frames: u32,
    /// How many times the accumulation's variance the squared difference between the two images
    /// must exceed before any of it counts as the denoised image's error.
    pub significance: f32,
}

impl Handoff {
    /// The learned denoiser's. Until 32 frames its own running means still grow (they average up
    /// to 32 frames), and estimates from fewer frames misjudged the scenes whose light arrives by
    /// rare paths (`blinds-room`, `covered-light`: twice the denoiser's error after 7 frames on an
    /// H100); a margin of 8 kept rare light's pixels from being handed over before it arrived
    /// (`training/README.md`).
    pub const NEURAL: Self = Self {
        first_frames: 32,
        significance: 8.0,
    };

    /// SVGF's (temporal mode). Its filter's blur is a larger error than the learned denoiser's,
    /// so every difference above the noise counts (a margin of 1: the unbiased estimate of the
    /// squared bias); on lavapipe 1 beat 3 and 8 on every scene tried, and 0.5 lost on
    /// `covered-light`. From 8 frames, handed over too early: on an H100 `blinds-room`'s DSSIM at
    /// 16 frames was 0.90 against SVGF's 0.54; from 16 it is SVGF's until then (`training/README.md`).
    pub const SVGF: Self = Self {
        first_frames: 16,
        significance: 1.0,
    };
}

/// Adds the hand-off of `denoised` to `inputs.accumulated` under the history key
/// `<prefix>.handoff.moment`, as `handoff` says; returns the image to show. Without accumulation,
/// and for the first [`Handoff::first_frames`] frames accumulated (a moving camera among them),
/// `denoised` is returned as it is.
pub fn add_handoff(
    g: &mut RenderGraph,
    inputs: &DenoiseInputs,
    denoised: ImageHandle,
    prefix: &str,
    handoff: Handoff,
) -> ImageHandle {
    if !inputs.accumulating {
        return denoised;
    }
    let (width, height) = (inputs.width, inputs.height);
    let moment = g.temporal_image(&history_key(prefix), ImageDesc::r32f(width, height));
    // Runs every frame, so that the second moment covers the frames the accumulated mean does.
    let mut pass = g.compute_pass(&format!("{prefix}.handoff.moment"), &MOMENT);
    pass.read("u_radiance", inputs.radiance)
        .read("u_accumulated", inputs.accumulated)
        .read("u_denoised", denoised);
    pass.history("u_prev_moment", "u_cur_moment", moment);
    let stats = pass.create_image(
        "u_stats",
        &format!("{prefix}.handoff.stats"),
        ImageDesc::new(width, height, vk::Format::R32G32_SFLOAT),
    );
    let accumulated = inputs.accumulated_frames;
    pass.push_with(move |ctx| {
        if ctx.history_valid(moment.prev) {
            accumulated
        } else {
            0
        }
    });
    pass.dispatch([width, height, 1]);
    if accumulated < handoff.first_frames {
        return denoised;
    }
    let mut pass = g.compute_pass(&format!("{prefix}.handoff.blend"), &BLEND);
    pass.read("u_accumulated", inputs.accumulated)
        .read("u_denoised", denoised)
        .read("u_stats", stats)
        .specialize("FIRST_FRAMES", handoff.first_frames)
        .specialize("SIGNIFICANCE", handoff.significance)
        .push(&accumulated);
    let output = pass.create_image(
        "u_output",
        &format!("{prefix}.handoff.output"),
        ImageDesc::rgba32f(width, height),
    );
    pass.dispatch([width, height, 1]);
    output
}

/// The history key of the running second moment under `prefix`.
pub fn history_key(prefix: &str) -> String {
    format!("{prefix}.handoff.moment")
}
