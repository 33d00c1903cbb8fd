//! FLIP's feature pipeline: edge and point detectors on the achromatic
//! channel, compared between reference and test.

use rayon::prelude::*;
use std::f32::consts::SQRT_2;

use super::super::plane::{kernel, normalized, Plane};

/// Peak-to-trough width, in degrees, of the human edge detector (twice its
/// standard deviation).
const DETECTOR_WIDTH_DEGREES: f32 = 0.082;

/// The three 1-D profiles whose products form the 2-D detectors.
pub(super) struct FeatureFilters {
    /// Gaussian, normalised to unit sum.
    smooth: Vec<f32>,
    /// First derivative of the Gaussian (edges), positive taps summing to 1
    /// and negative taps to -1.
    edge: Vec<f32>,
    /// Second derivative of the Gaussian (points), normalised like `edge`.
    point: Vec<f32>,
}

/// Scales positive taps to sum to 1 and negative taps to sum to -1.
fn balanced(kernel: Vec<f32>) -> Vec<f32> {
    let positive: f32 = kernel.iter().filter(|w| **w > 0.0).sum();
    let negative: f32 = -kernel.iter().filter(|w| **w < 0.0).sum::<f32>();
    kernel
        .into_iter()
        .map(|w| {
            if w > 0.0 {
                w / positive
            } else if w < 0.0 {
                w / negative
            } else {
                0.0
            }
        })
        .collect()
}

impl FeatureFilters {
    /// Builds the detectors for `pixels_per_degree`.
    pub fn new(pixels_per_degree: f32) -> Self {
        let sigma = 0.5 * DETECTOR_WIDTH_DEGREES * pixels_per_degree;
        let radius = (3.0 * sigma).ceil() as usize;
        let gaussian = |x: f32| (-x * x / (2.0 * sigma * sigma)).exp();
        Self {
            smooth: normalized(kernel(radius, gaussian)),
            edge: balanced(kernel(radius, |x| -x * gaussian(x))),
            point: balanced(kernel(radius, |x| {
                (x * x / (sigma * sigma) - 1.0) * gaussian(x)
            })),
        }
    }

    /// Edge and point response magnitudes of a luminance plane in `[0, 1]`.
    pub fn responses(&self, luminance: &Plane) -> Responses {
        // Smoothed along x once: the y derivatives of both detectors start from it.
        let smooth_rows = luminance.filter_rows(&self.smooth);
        let magnitude = |profile: &[f32]| {
            let along_x = luminance.filter_rows(profile).filter_columns(&self.smooth);
            let along_y = smooth_rows.filter_columns(profile);
            along_x.zip_map(&along_y, |a, b| (a * a + b * b).sqrt())
        };
        Responses {
            edges: magnitude(&self.edge),
            points: magnitude(&self.point),
        }
    }
}

/// The edge and point detector magnitudes of one image.
pub(super) struct Responses {
    edges: Plane,
    points: Plane,
}

/// Per-pixel feature difference in `[0, 1]`: the larger of the edge and point magnitude
/// differences, scaled by `1 / sqrt(2)` and compressed with the exponent 0.5 (a square root).
pub(super) fn feature_difference(reference: &Responses, test: &Responses) -> Vec<f32> {
    (0..reference.edges.data.len())
        .into_par_iter()
        .map(|i| {
            let edge = (reference.edges.data[i] - test.edges.data[i]).abs();
            let point = (reference.points.data[i] - test.points.data[i]).abs();
            (edge.max(point) / SQRT_2).sqrt()
        })
        .collect()
}
