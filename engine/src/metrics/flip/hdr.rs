//! HDR-FLIP (Andersson et al. 2021, "Visualizing Errors in Rendered High Dynamic Range Images"):
//! LDR-FLIP of the two images exposed and tone-mapped at exposures spread over the reference's
//! range, the per-pixel maximum over exposures. Exposure range, tone curve and step count follow
//! NVIDIA's `flip_evaluator` defaults (ACES with its 0.6 pre-exposure cancelled, exposures from
//! where the brightest reference pixel to where the median one maps to 0.85, one per stop).

use super::{flip, FlipResult};
use crate::capture::{rec709_luminance, ImageData};
use crate::metrics::check::{check_pair, check_parameter};
use crate::metrics::MetricsError;

/// The ACES fit FLIP tone-maps with, as `(a x² + b x + c) / (d x² + e x + f)` (0.6 is the
/// pre-exposure the fit assumes, cancelled).
const ACES: [f32; 6] = [
    0.6 * 0.6 * 2.51,
    0.6 * 0.03,
    0.0,
    0.6 * 0.6 * 2.43,
    0.6 * 0.59,
    0.14,
];

/// The tone-mapped value the exposure range is placed by.
const EXPOSURE_TARGET: f32 = 0.85;

/// How HDR-FLIP exposes the images.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HdrFlipParams {
    /// Pixels per degree of visual angle (as for [`flip`]).
    pub pixels_per_degree: f64,
    /// The lowest exposure, in stops.
    pub start_exposure: f64,
    /// The highest exposure, in stops.
    pub stop_exposure: f64,
    /// Exposures evaluated, evenly spaced from start to stop (at least 2).
    pub exposures: u32,
}

impl HdrFlipParams {
    /// `flip_evaluator`'s defaults for `reference`: from the exposure at which its brightest
    /// pixel's luminance tone-maps to 0.85 to the one at which its median luminance does, one
    /// exposure per stop (at least 2).
    pub fn for_reference(reference: &ImageData, pixels_per_degree: f64) -> Self {
        let (a, b, c) = (
            ACES[0] - EXPOSURE_TARGET * ACES[3],
            ACES[1] - EXPOSURE_TARGET * ACES[4],
            ACES[2] - EXPOSURE_TARGET * ACES[5],
        );
        let x_max = larger_root(a, b, c);
        let mut luminance: Vec<f32> = reference
            .pixels
            .iter()
            .map(|&p| rec709_luminance(p))
            .collect();
        let max = luminance.iter().copied().fold(f32::MIN, f32::max);
        let middle = luminance.len() / 2;
        let median = if luminance.is_empty() {
            0.0
        } else {
            *luminance.select_nth_unstable_by(middle, f32::total_cmp).1
        };
        let start = (x_max / max).log2();
        let stop = (x_max / median).log2();
        Self {
            pixels_per_degree,
            start_exposure: f64::from(start),
            stop_exposure: f64::from(stop),
            exposures: (stop - start).ceil().max(2.0) as u32,
        }
    }
}

/// The larger root of `a x² + b x + c`.
fn larger_root(a: f32, b: f32, c: f32) -> f32 {
    if a == 0.0 {
        return -c / b;
    }
    let half = -0.5 * b / a;
    let spread = (half * half - c / a).sqrt();
    (half - spread).max(half + spread)
}

/// FLIP's tone curve of one linear value.
fn tone_map(x: f32) -> f32 {
    (x * x * ACES[0] + x * ACES[1] + ACES[2]) / (x * x * ACES[3] + x * ACES[4] + ACES[5])
}

/// HDR-FLIP of linear HDR `test` against `reference`: per pixel, the largest LDR-FLIP over the
/// exposures of `params` (each image scaled by `2^exposure`, tone-mapped, clamped to [0, 1]).
pub fn hdr_flip(
    test: &ImageData,
    reference: &ImageData,
    params: &HdrFlipParams,
) -> Result<FlipResult, MetricsError> {
    check_pair(test, reference)?;
    let (start, stop) = (params.start_exposure, params.stop_exposure);
    check_parameter(
        "exposure range",
        stop - start,
        start.is_finite() && stop.is_finite() && start <= stop,
        "start and stop must be finite, start at most stop",
    )?;
    check_parameter(
        "exposures",
        f64::from(params.exposures),
        params.exposures >= 2,
        "must be at least 2",
    )?;
    let step = (stop - start) as f32 / (params.exposures - 1) as f32;
    let exposed = |image: &ImageData, exposure: f32| {
        let scale = exposure.exp2();
        let pixels = image
            .pixels
            .iter()
            .map(|p| {
                let c = |v: f32| tone_map(v * scale).clamp(0.0, 1.0);
                [c(p[0]), c(p[1]), c(p[2]), p[3]]
            })
            .collect();
        ImageData::from_pixels(image.width, image.height, pixels)
            .expect("the size of a checked image")
    };
    let mut worst: Option<FlipResult> = None;
    for i in 0..params.exposures {
        let exposure = start as f32 + i as f32 * step;
        let ldr = flip(
            &exposed(test, exposure),
            &exposed(reference, exposure),
            params.pixels_per_degree,
        )?;
        worst = Some(match worst {
            None => ldr,
            Some(mut max) => {
                for (m, e) in max.error_map.iter_mut().zip(&ldr.error_map) {
                    *m = m.max(*e);
                }
                max
            }
        });
    }
    let mut result = worst.expect("at least two exposures");
    result.mean =
        result.error_map.iter().map(|&e| f64::from(e)).sum::<f64>() / result.error_map.len() as f64;
    Ok(result)
}
