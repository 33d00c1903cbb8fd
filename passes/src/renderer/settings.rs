//! What a frame renders: algorithm, samples, depth, accumulation and display settings. The
//! command line, the sandbox's panels and embedding code all use these types; with the `clap`
//! feature, [`Algorithm`], [`Denoiser`] and [`EdgeEmission`] are `clap::ValueEnum`s
//! (`renderer/value_enum.rs`).

use crate::denoise::neural::NeuralParams;
use crate::denoise::svgf::SvgfParams;
use crate::light_transport::bdpt::{MisHeuristic, DEFAULT_CONNECTION_ROULETTE};
use crate::samples_per_pixel::SamplesPerPixel;
use lucid_engine::capture::{PngEncoding, ToneCurve};
use std::num::NonZeroU32;

/// The light-transport algorithm, switchable per frame.
///
/// ```
/// use lucid_passes::renderer::Algorithm;
/// assert_eq!(
///     Algorithm::ALL.map(Algorithm::label),
///     [
///         "path tracing",
///         "bidirectional",
///         "path tracing (wavefront)",
///         "path tracing (wavefront, material bins)"
///     ]
/// );
/// assert_eq!(
///     Algorithm::ALL.map(Algorithm::short_name),
///     ["pt", "bdpt", "pt-wavefront", "pt-wavefront-binned"]
/// );
/// assert_eq!(Algorithm::PathTracing.other(), Algorithm::Bidirectional);
/// assert_eq!(Algorithm::PathTracingWavefront.other(), Algorithm::PathTracing);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Algorithm {
    /// Unidirectional path tracing with NEE and MIS.
    #[default]
    PathTracing,
    /// Bidirectional path tracing with a light vertex cache.
    Bidirectional,
    /// Path tracing's estimator (the same random numbers, replay included) as a wavefront:
    /// generate, extend, shade and shadow kernels over queues of paths
    /// ([`crate::light_transport::wavefront`]).
    PathTracingWavefront,
    /// The wavefront path tracer with each bounce's hits binned by material kind before shading
    /// ([`crate::light_transport::wavefront::Config::bin_by_material`]).
    PathTracingWavefrontBinned,
}

impl Algorithm {
    /// Every algorithm, in the order menus and the command line list them.
    pub const ALL: [Algorithm; 4] = [
        Algorithm::PathTracing,
        Algorithm::Bidirectional,
        Algorithm::PathTracingWavefront,
        Algorithm::PathTracingWavefrontBinned,
    ];

    /// Whether the algorithm can replay last frame's paths where asked (SVGF's temporal gradients
    /// need it; `shaders/common/replay.glsl`). Bidirectional path tracing cannot: its camera paths
    /// connect to this frame's light vertex cache.
    pub fn replays_paths(self) -> bool {
        self != Algorithm::Bidirectional
    }

    /// The short name used on the command line and in reports (`pt`, `bdpt`, `pt-wavefront`,
    /// `pt-wavefront-binned`).
    pub fn short_name(self) -> &'static str {
        match self {
            Algorithm::PathTracing => "pt",
            Algorithm::Bidirectional => "bdpt",
            Algorithm::PathTracingWavefront => "pt-wavefront",
            Algorithm::PathTracingWavefrontBinned => "pt-wavefront-binned",
        }
    }

    /// The name shown in user interfaces (`path tracing`, `bidirectional`,
    /// `path tracing (wavefront)`, `path tracing (wavefront, material bins)`).
    pub fn label(self) -> &'static str {
        match self {
            Algorithm::PathTracing => "path tracing",
            Algorithm::Bidirectional => "bidirectional",
            Algorithm::PathTracingWavefront => "path tracing (wavefront)",
            Algorithm::PathTracingWavefrontBinned => "path tracing (wavefront, material bins)",
        }
    }

    /// The algorithm to compare with (what a side-by-side comparison shows by default): path
    /// tracing and BDPT each other, the wavefront path tracers the megakernel.
    pub fn other(self) -> Self {
        match self {
            Algorithm::PathTracing => Algorithm::Bidirectional,
            Algorithm::Bidirectional
            | Algorithm::PathTracingWavefront
            | Algorithm::PathTracingWavefrontBinned => Algorithm::PathTracing,
        }
    }
}

/// The denoiser applied after tracing.
///
/// ```
/// use lucid_passes::renderer::Denoiser;
/// assert_eq!(Denoiser::ALL.map(Denoiser::label), ["none", "SVGF", "learned"]);
/// assert_eq!(Denoiser::ALL.map(Denoiser::short_name), ["none", "svgf", "neural"]);
/// ```
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

impl Denoiser {
    /// Every denoiser, in the order menus and the command line list them.
    pub const ALL: [Denoiser; 3] = [Denoiser::None, Denoiser::Svgf, Denoiser::Neural];

    /// The short name used on the command line (`none`, `svgf`, `neural`).
    pub fn short_name(self) -> &'static str {
        match self {
            Denoiser::None => "none",
            Denoiser::Svgf => "svgf",
            Denoiser::Neural => "neural",
        }
    }

    /// The name shown in user interfaces (`none`, `SVGF`, `learned`).
    pub fn label(self) -> &'static str {
        match self {
            Denoiser::None => "none",
            Denoiser::Svgf => "SVGF",
            Denoiser::Neural => "learned",
        }
    }

    /// Whether the denoiser supersamples the emission it adds back at emitters' edges unless told
    /// otherwise ([`EdgeEmission::ByDenoiser`]). The learned denoiser does: on the held-out
    /// `classroom` path it flickers 45% less with the pass (`training/README.md`), and the lavapipe
    /// pan holds it to 0.2x a per-frame filter that has the pass too. SVGF does not: its history,
    /// cut where the centre's object changes, flickers at 0.216x there.
    pub fn supersamples_edges_by_default(self) -> bool {
        matches!(self, Denoiser::Neural)
    }
}

/// Whether the emission the denoisers add back is supersampled at emitters' edges
/// ([`crate::denoise::edge_emission`]).
///
/// ```
/// use lucid_passes::renderer::{Denoiser, EdgeEmission};
/// assert_eq!(EdgeEmission::ALL.map(EdgeEmission::short_name), ["auto", "on", "off"]);
/// assert!(EdgeEmission::ByDenoiser.enabled_for(Denoiser::Neural));
/// assert!(!EdgeEmission::ByDenoiser.enabled_for(Denoiser::Svgf));
/// assert!(EdgeEmission::On.enabled_for(Denoiser::Svgf));
/// assert!(!EdgeEmission::Off.enabled_for(Denoiser::Neural));
/// assert!(!EdgeEmission::On.enabled_for(Denoiser::None), "nothing adds emission back");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum EdgeEmission {
    /// As the denoiser chooses ([`Denoiser::supersamples_edges_by_default`]).
    #[default]
    ByDenoiser,
    /// For every denoiser.
    On,
    /// For none.
    Off,
}

impl EdgeEmission {
    /// Every choice, in the order menus and the command line list them.
    pub const ALL: [EdgeEmission; 3] = [
        EdgeEmission::ByDenoiser,
        EdgeEmission::On,
        EdgeEmission::Off,
    ];

    /// The short name used on the command line (`auto`, `on`, `off`).
    pub fn short_name(self) -> &'static str {
        match self {
            EdgeEmission::ByDenoiser => "auto",
            EdgeEmission::On => "on",
            EdgeEmission::Off => "off",
        }
    }

    /// The name shown in user interfaces.
    pub fn label(self) -> &'static str {
        match self {
            EdgeEmission::ByDenoiser => "as the denoiser chooses",
            EdgeEmission::On => "on",
            EdgeEmission::Off => "off",
        }
    }

    /// Whether the pass runs under `denoiser` (never without one: nothing adds emission back).
    pub fn enabled_for(self, denoiser: Denoiser) -> bool {
        denoiser != Denoiser::None
            && match self {
                EdgeEmission::ByDenoiser => denoiser.supersamples_edges_by_default(),
                EdgeEmission::On => true,
                EdgeEmission::Off => false,
            }
    }
}

/// Render settings. Changing anything but exposure, tone curve and what runs of the learned
/// denoiser ([`Settings::neural`], on which neither the samples nor its history depend) restarts
/// accumulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The light-transport algorithm.
    pub algorithm: Algorithm,
    /// Samples per pixel per frame.
    pub samples_per_pixel: SamplesPerPixel,
    /// Longest path, in Mitsuba's convention (1: emitters seen directly, 2: direct lighting, ...).
    pub max_depth: u32,
    /// Depth from which Russian roulette may end paths.
    pub rr_depth: u32,
    /// Path tracing and BDPT's camera subpaths with one sample a pixel, up to 1920x1080 pixels:
    /// the paths still alive after `rr_depth` segments are continued by a second kernel over a
    /// compacted list rather than holding the first kernel's subgroups
    /// (`lucid_passes::light_transport::path_trace::Config`, `bdpt::Config`); the same paths and
    /// random numbers either way.
    pub park_long_paths: bool,
    /// Cached light vertices each BDPT camera vertex connects to: more connections cost time and
    /// lower the noise of the light that only connections find.
    pub bdpt_connections: NonZeroU32,
    /// How BDPT's multiple importance sampling weighs its strategies: the power heuristic, or the
    /// balance heuristic (for comparisons).
    pub bdpt_mis: MisHeuristic,
    /// BDPT's connection roulette: before Russian roulette's start, a connection that would add
    /// less than this share of what its camera subpath has gathered is traced with probability
    /// in proportion and weighted up (unbiased; fewer shadow rays, a little more noise), and so is
    /// a light-tracing connection to the camera whose MIS weight is under this share (at most 1);
    /// 0 traces every connection. Negative or non-finite values count as 0.
    pub bdpt_connection_roulette: f32,
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
    /// Whether the emission the denoisers add back is supersampled at emitters' edges.
    pub edge_emission: EdgeEmission,
    /// What the learned denoiser runs of its weights.
    pub neural: NeuralParams,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            algorithm: Algorithm::PathTracing,
            samples_per_pixel: SamplesPerPixel::ONE,
            max_depth: 8,
            rr_depth: 5,
            park_long_paths: true,
            bdpt_connections: NonZeroU32::MIN,
            bdpt_mis: MisHeuristic::Power,
            bdpt_connection_roulette: DEFAULT_CONNECTION_ROULETTE,
            seed: 0,
            accumulate: true,
            display: PngEncoding {
                exposure: 0.0,
                tone: ToneCurve::Aces,
            },
            denoiser: Denoiser::None,
            svgf: SvgfParams::default(),
            edge_emission: EdgeEmission::ByDenoiser,
            neural: NeuralParams::default(),
        }
    }
}

impl Settings {
    /// Whether this frame's denoiser supersamples the emission at emitters' edges.
    pub fn supersamples_edges(&self) -> bool {
        self.edge_emission.enabled_for(self.denoiser)
    }

    /// Whether going from `self` to `other` invalidates accumulated samples.
    ///
    /// ```
    /// use lucid_passes::denoise::neural::NeuralParams;
    /// use lucid_passes::renderer::Settings;
    /// let settings = Settings::default();
    /// let unfiltered = Settings {
    ///     neural: NeuralParams { gated_filter: false },
    ///     ..settings
    /// };
    /// assert!(!settings.restarts_accumulation(&unfiltered));
    /// assert!(settings.restarts_accumulation(&Settings { seed: 1, ..settings }));
    /// ```
    pub fn restarts_accumulation(&self, other: &Settings) -> bool {
        Settings {
            display: other.display,
            neural: other.neural,
            ..*self
        } != *other
    }
}
