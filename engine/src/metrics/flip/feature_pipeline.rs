//! FLIP's feature pipeline: edge and point detectors on the achromatic
//! channel, compared between reference and test.

use std::f32::consts::SQRT_2;

use super::super::plane::{kernel, normalized, Plane};

/// Peak-to-trough width, in degrees, of the human edge detector (twice its
/// standard deviation).
const DETECTOR_WIDTH_DEGREES: f32 = 0.082;
/// Exponent compressing the feature difference.
const QF: f32 = 0.5;

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
    fn responses(&self, luminance: &Plane) -> (Plane, Plane) {
        let magnitude = |profile: &[f32]| {
            let along_x = luminance.filter(profile, &self.smooth);
            let along_y = luminance.filter(&self.smooth, profile);
            along_x.zip_map(&along_y, |a, b| a.hypot(b))
        };
        (magnitude(&self.edge), magnitude(&self.point))
    }

    /// Per-pixel feature difference in `[0, 1]`: the larger of the edge and
    /// point magnitude differences, scaled by `1 / sqrt(2)` and compressed
    /// with the exponent 0.5.
    pub fn difference(&self, reference: &Plane, test: &Plane) -> Vec<f32> {
        let (ref_edges, ref_points) = self.responses(reference);
        let (test_edges, test_points) = self.responses(test);
        (0..reference.data.len())
            .map(|i| {
                let edge = (ref_edges.data[i] - test_edges.data[i]).abs();
                let point = (ref_points.data[i] - test_points.data[i]).abs();
                (edge.max(point) / SQRT_2).powf(QF)
            })
            .collect()
    }
}
