//! What a frame renders: algorithm, samples, depth, accumulation and display settings.

use crate::denoise::svgf::SvgfParams;
use lucid_engine::capture::{PngEncoding, ToneCurve};

/// The light-transport algorithm, switchable per frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Algorithm {
    /// Unidirectional path tracing with NEE and MIS.
    #[default]
    PathTracing,
    /// Bidirectional path tracing with a light vertex cache.
    Bidirectional,
}

impl Algorithm {
    /// Every algorithm, for menus and argument parsing.
    pub const ALL: [Algorithm; 2] = [Algorithm::PathTracing, Algorithm::Bidirectional];

    /// Whether the algorithm can replay last frame's paths where asked (SVGF's temporal gradients
    /// need it; `shaders/common/replay.glsl`). Bidirectional path tracing cannot: its camera paths
    /// connect to this frame's light vertex cache.
    pub fn replays_paths(self) -> bool {
        self == Algorithm::PathTracing
    }

    /// The short name used on the command line (`pt`, `bdpt`).
    pub fn short_name(self) -> &'static str {
        match self {
            Algorithm::PathTracing => "pt",
            Algorithm::Bidirectional => "bdpt",
        }
    }

    /// Parses a short name.
    pub fn from_short_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|a| a.short_name() == name)
    }
}

/// The denoiser applied after tracing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Denoiser {
    /// The (accumulated) radiance as traced.
    #[default]
    None,
    /// SVGF, in the mode of [`SvgfParams::mode`].
    Svgf,
    /// The learned recurrent denoiser ([`crate::denoise::neural`]).
    Neural,
}

/// Render settings. Changing anything but exposure and tone curve restarts accumulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The light-transport algorithm.
    pub algorithm: Algorithm,
    /// Samples per pixel per frame.
    pub samples_per_pixel: u32,
    /// Longest path, in Mitsuba's convention (1: emitters seen directly, 2: direct lighting, ...).
    pub max_depth: u32,
    /// Depth from which Russian roulette may end paths.
    pub rr_depth: u32,
    /// Seed of the per-pixel random numbers.
    pub seed: u32,
    /// Average frames while camera and scene are still.
    pub accumulate: bool,
    /// Exposure (stops) and tone curve of the displayed image.
    pub display: PngEncoding,
    /// The denoiser.
    pub denoiser: Denoiser,
    /// The SVGF denoiser's parameters.
    pub svgf: SvgfParams,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            algorithm: Algorithm::PathTracing,
            samples_per_pixel: 1,
            max_depth: 8,
            rr_depth: 5,
            seed: 0,
            accumulate: true,
            display: PngEncoding {
                exposure: 0.0,
                tone: ToneCurve::Aces,
            },
            denoiser: Denoiser::None,
            svgf: SvgfParams::default(),
        }
    }
}

impl Settings {
    /// Whether going from `self` to `other` invalidates accumulated samples.
    pub fn restarts_accumulation(&self, other: &Settings) -> bool {
        Settings {
            display: other.display,
            ..*self
        } != *other
    }
}
