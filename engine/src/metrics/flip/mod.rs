//! LDR-FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for
//! Alternating Images"), implemented from the paper and its published
//! constants.
//!
//! Both images go to the YCxCz opponent space. The colour pipeline filters
//! them with contrast-sensitivity functions for the viewing distance and
//! compares them in Hunt-adjusted L*a*b* with HyAB; the feature pipeline
//! compares edge and point detector responses on luminance. Per pixel,
//! `FLIP = colour_error ^ (1 - feature_error)`, in `[0, 1]`.

mod color;
mod color_pipeline;
mod feature_pipeline;
mod hdr;

pub use hdr::{hdr_flip, HdrFlipParams};

use rayon::prelude::*;

use super::check::{check_image, check_pair, check_parameter, check_size};
use super::plane::{clamp_unit, Plane};
use super::sum::ordered_sum;
use super::MetricsError;
use crate::capture::ImageData;
use color::{linear_rgb_to_ycxcz, ycxcz_luminance};
use color_pipeline::{color_difference, hunt_lab, CsfFilters, Opponent};
use feature_pipeline::{feature_difference, FeatureFilters, Responses};

/// The reference implementation's default observer: a 0.7 m wide 3840-pixel
/// monitor viewed from 0.7 m, `0.7 * (3840 / 0.7) * pi / 180` ≈ 67.0206 pixels
/// per degree of visual angle.
pub const DEFAULT_PIXELS_PER_DEGREE: f64 = 3840.0 * std::f64::consts::PI / 180.0;

/// Largest accepted pixels-per-degree: filter sizes grow linearly with it.
const MAX_PIXELS_PER_DEGREE: f64 = 1000.0;

/// The outcome of [`flip`].
#[derive(Debug, Clone, PartialEq)]
pub struct FlipResult {
    /// Mean of `error_map`: the single-number FLIP score, in `[0, 1]`.
    pub mean: f64,
    /// Width of `error_map`.
    pub width: u32,
    /// Height of `error_map`.
    pub height: u32,
    /// Per-pixel FLIP error in `[0, 1]`, row-major, top row first.
    pub error_map: Vec<f32>,
}

/// LDR-FLIP of `test` against `reference` for an observer seeing
/// `pixels_per_degree` pixels per degree of visual angle (use
/// [`DEFAULT_PIXELS_PER_DEGREE`] unless the viewing setup is known).
///
/// The images are read as linear display light: R, G, B are clamped to
/// `[0, 1]` (NaN counts as 0), which is the reference implementation's
/// input after its sRGB decode. For linear HDR frames, compare
/// [`PngEncoding::tone_map`](crate::capture::PngEncoding::tone_map) of both
/// images. Identical images give exactly 0.
pub fn flip(
    test: &ImageData,
    reference: &ImageData,
    pixels_per_degree: f64,
) -> Result<FlipResult, MetricsError> {
    check_pair(test, reference)?;
    FlipReference::new(reference, pixels_per_degree)?.compare(test)
}

/// A reference image prepared for [`flip`] against many test images: its contrast-sensitivity
/// filtered opponent colours and its edge and point responses, computed once.
pub struct FlipReference {
    csf: CsfFilters,
    features: FeatureFilters,
    /// The reference's CSF-filtered colours in Hunt-adjusted L*a*b*.
    lab: Vec<[f32; 3]>,
    responses: Responses,
    size: (u32, u32),
}

impl FlipReference {
    /// Prepares `reference` (linear display light, clamped to [0, 1]) for an observer seeing
    /// `pixels_per_degree` pixels per degree.
    pub fn new(reference: &ImageData, pixels_per_degree: f64) -> Result<Self, MetricsError> {
        check_image(reference)?;
        check_parameter(
            "pixels_per_degree",
            pixels_per_degree,
            pixels_per_degree > 0.0 && pixels_per_degree <= MAX_PIXELS_PER_DEGREE,
            "must be in (0, 1000]",
        )?;
        let ppd = pixels_per_degree as f32;
        let csf = CsfFilters::new(ppd);
        let features = FeatureFilters::new(ppd);
        let opponent = opponent(reference);
        let responses = features.responses(&opponent.y.map(ycxcz_luminance));
        Ok(Self {
            lab: hunt_lab(&csf.apply(&opponent)),
            csf,
            features,
            responses,
            size: (reference.width, reference.height),
        })
    }

    /// LDR-FLIP of `test` (the reference's size) against the prepared reference.
    pub fn compare(&self, test: &ImageData) -> Result<FlipResult, MetricsError> {
        check_image(test)?;
        check_size(test, self.size)?;
        let (width, height) = self.size;
        let test = opponent(test);
        let color_error = color_difference(&self.lab, &hunt_lab(&self.csf.apply(&test)));
        let test_responses = self.features.responses(&test.y.map(ycxcz_luminance));
        let feature_error = feature_difference(&self.responses, &test_responses);
        let error_map: Vec<f32> = color_error
            .par_iter()
            .zip(&feature_error)
            .map(|(&c, &f)| c.powf(1.0 - f))
            .collect();
        let mean =
            ordered_sum(error_map.len(), |i| f64::from(error_map[i])) / error_map.len() as f64;
        Ok(FlipResult {
            mean,
            width,
            height,
            error_map,
        })
    }
}

/// The image in YCxCz, its R, G, B clamped to `[0, 1]` first (one conversion per pixel).
fn opponent(image: &ImageData) -> Opponent {
    let ycxcz: Vec<[f32; 3]> = image
        .pixels
        .par_iter()
        .map(|p| linear_rgb_to_ycxcz([p[0], p[1], p[2]].map(clamp_unit)))
        .collect();
    let channel = |c: usize| Plane {
        width: image.width as usize,
        height: image.height as usize,
        data: ycxcz.par_iter().map(|v| v[c]).collect(),
    };
    Opponent {
        y: channel(0),
        cx: channel(1),
        cz: channel(2),
    }
}
