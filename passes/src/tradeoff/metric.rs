//! The errors a configuration is measured by.

use super::measure::Measurement;

/// An error of a frame against the reference (as `lucid evaluate` computes it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Metric {
    /// `1 / SSIM - 1` of the display-encoded images (the study's DSSIM; `--algo auto`'s default:
    /// at small sizes FLIP, made for a 67-pixels-per-degree viewing, takes a denoiser's
    /// smoothing of fine detail for error more than it credits the noise removed).
    #[default]
    Dssim,
    /// Mean LDR-FLIP of the tone-mapped images.
    Flip,
    /// Relative MSE of the linear images.
    RelMse,
}

impl Metric {
    /// Every metric, in the CSV's column order.
    pub const ALL: [Metric; 3] = [Metric::Dssim, Metric::Flip, Metric::RelMse];

    /// The name in CSV, JSON and file names and on the command line (`dssim`, `flip`, `rel_mse`).
    pub fn name(self) -> &'static str {
        match self {
            Metric::Dssim => "dssim",
            Metric::Flip => "flip",
            Metric::RelMse => "rel_mse",
        }
    }

    /// The name on charts and in reasons (`DSSIM`, `FLIP`, `relMSE`).
    pub fn label(self) -> &'static str {
        match self {
            Metric::Dssim => "DSSIM",
            Metric::Flip => "FLIP",
            Metric::RelMse => "relMSE",
        }
    }

    /// This metric of a measurement.
    pub fn of(self, row: &Measurement) -> f64 {
        match self {
            Metric::Dssim => row.dssim,
            Metric::Flip => row.flip,
            Metric::RelMse => row.rel_mse,
        }
    }
}
