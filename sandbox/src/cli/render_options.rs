//! Options shared by `render` and `bench`: scene, algorithm, samples, depth, size, seed, display.

use super::size::Size;
use clap::{Args, ValueEnum};
use lucid_engine::capture::{PngEncoding, ToneCurve};
use lucid_passes::renderer::{Algorithm, Denoiser, Settings};

/// The light-transport algorithm on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AlgoArg {
    /// Path tracing (NEE, MIS, Russian roulette).
    Pt,
    /// Bidirectional path tracing (light vertex cache, MIS).
    Bdpt,
}

/// The denoiser on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DenoiseArg {
    /// No denoiser.
    None,
    /// SVGF (temporal, with A-SVGF gradients).
    Svgf,
    /// The learned recurrent denoiser.
    Neural,
}

/// The tone curve on the command line.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum ToneArg {
    /// Clamp to [0, 1].
    Clamp,
    /// The ACES filmic fit.
    Aces,
    /// AgX.
    Agx,
}

/// What to render and how.
#[derive(Debug, Args)]
pub struct RenderOptions {
    /// A built-in scene (see `lucid scenes`) or a .gltf/.glb file.
    #[arg(long, default_value = "cornell-box")]
    pub scene: String,
    /// Light-transport algorithm.
    #[arg(long, value_enum, default_value_t = AlgoArg::Pt)]
    pub algo: AlgoArg,
    /// Samples per pixel per frame.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub spp: u32,
    /// Longest path (Mitsuba's convention: 1 = emitters only, 2 = direct light, ...).
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub max_depth: u32,
    /// Image size.
    #[arg(long, default_value = "512x512")]
    pub size: Size,
    /// Seed of the random numbers.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Exposure in stops.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f32,
    /// Tone curve for PNG output and display.
    #[arg(long, value_enum, default_value_t = ToneArg::Aces)]
    pub tone: ToneArg,
    /// Denoiser applied after tracing.
    #[arg(long, value_enum, default_value_t = DenoiseArg::None)]
    pub denoise: DenoiseArg,
}

impl RenderOptions {
    /// The renderer settings these options describe.
    pub fn settings(&self, accumulate: bool) -> Settings {
        Settings {
            algorithm: match self.algo {
                AlgoArg::Pt => Algorithm::PathTracing,
                AlgoArg::Bdpt => Algorithm::Bidirectional,
            },
            samples_per_pixel: self.spp,
            max_depth: self.max_depth,
            seed: self.seed,
            accumulate,
            display: self.display(),
            denoiser: match self.denoise {
                DenoiseArg::None => Denoiser::None,
                DenoiseArg::Svgf => Denoiser::Svgf,
                DenoiseArg::Neural => Denoiser::Neural,
            },
            ..Settings::default()
        }
    }

    /// Exposure and tone curve.
    pub fn display(&self) -> PngEncoding {
        PngEncoding {
            exposure: self.exposure,
            tone: match self.tone {
                ToneArg::Clamp => ToneCurve::Clamp,
                ToneArg::Aces => ToneCurve::Aces,
                ToneArg::Agx => ToneCurve::AgX,
            },
        }
    }
}
