//! `clap::ValueEnum` for [`Algorithm`], [`Denoiser`], [`EdgeEmission`], [`MisHeuristic`],
//! [`InferencePath`] and [`Metric`] (the `clap` feature): the command line
//! accepts their short names, case-insensitively where a caller asks.

use super::{Algorithm, Denoiser, EdgeEmission};
use crate::denoise::neural::InferencePath;
use crate::light_transport::bdpt::MisHeuristic;
use crate::tradeoff::Metric;
use clap::builder::PossibleValue;
use clap::ValueEnum;

impl ValueEnum for Algorithm {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self {
            Algorithm::PathTracing => "Path tracing (NEE, MIS, Russian roulette)",
            Algorithm::Bidirectional => "Bidirectional path tracing (light vertex cache, MIS)",
            Algorithm::PathTracingWavefront => {
                "Path tracing as a wavefront: generate, extend, shade and shadow kernels over queues"
            }
            Algorithm::PathTracingWavefrontBinned => {
                "Wavefront path tracing, each bounce's hits binned by material kind before shading"
            }
        };
        Some(PossibleValue::new(self.short_name()).help(help))
    }
}

impl ValueEnum for Denoiser {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self {
            Denoiser::None => "No denoiser",
            Denoiser::Svgf => "SVGF (temporal, with A-SVGF gradients)",
            Denoiser::Neural => "The learned recurrent denoiser",
        };
        Some(PossibleValue::new(self.short_name()).help(help))
    }
}

impl ValueEnum for MisHeuristic {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self {
            MisHeuristic::Power => "Power heuristic, exponent 2",
            MisHeuristic::Balance => "Balance heuristic",
        };
        Some(PossibleValue::new(self.short_name()).help(help))
    }
}

impl ValueEnum for EdgeEmission {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self {
            EdgeEmission::ByDenoiser => {
                "As the denoiser chooses: the learned denoiser's, not SVGF's"
            }
            EdgeEmission::On => "For every denoiser",
            EdgeEmission::Off => "For none",
        };
        Some(PossibleValue::new(self.short_name()).help(help))
    }
}

impl ValueEnum for InferencePath {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self {
            InferencePath::Portable => "Plain compute shaders: every device",
            InferencePath::TensorCores => "NVIDIA cooperative matrices (VK_NV_cooperative_matrix)",
        };
        Some(PossibleValue::new(self.short_name()).help(help))
    }
}

impl ValueEnum for Metric {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let value = PossibleValue::new(self.name());
        Some(match self {
            Metric::Dssim => value.help("1/SSIM - 1 of the luminance of the display images"),
            Metric::Flip => value.help("Mean LDR-FLIP of the tone-mapped images"),
            Metric::RelMse => value
                .alias("relmse")
                .help("Relative MSE of the linear images"),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_command_line_accepts_the_short_names() {
        for algorithm in Algorithm::ALL {
            assert_eq!(
                Algorithm::from_str(algorithm.short_name(), false),
                Ok(algorithm)
            );
        }
        assert_eq!(
            Algorithm::from_str("BDPT", true),
            Ok(Algorithm::Bidirectional)
        );
        assert_eq!(Denoiser::from_str("svgf", false), Ok(Denoiser::Svgf));
        assert_eq!(Denoiser::from_str("none", false), Ok(Denoiser::None));
        assert!(Denoiser::from_str("oidn", true).is_err());
        assert_eq!(Metric::from_str("flip", false), Ok(Metric::Flip));
        assert_eq!(Metric::from_str("relmse", false), Ok(Metric::RelMse));
    }
}
