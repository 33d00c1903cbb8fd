//! FLIP's colour pipeline: contrast-sensitivity filtering in YCxCz, then the
//! Hunt-adjusted HyAB difference, compressed and remapped to `[0, 1]`.

use rayon::prelude::*;
use std::f32::consts::PI;

use super::super::plane::{kernel, normalized, Plane};
use super::color::{hyab, linear_rgb_to_hunt_lab, ycxcz_to_linear_rgb};

/// Exponent compressing the HyAB distance.
const QC: f32 = 0.7;
/// Fraction of the maximum error below which errors are mapped linearly...
const PC: f32 = 0.4;
/// ...onto `[0, PT]`; larger errors are mapped onto `(PT, 1]`.
const PT: f32 = 0.95;

/// Scale parameter `b` of the achromatic CSF, a single Gaussian term (its
/// amplitude cancels in normalisation).
const CSF_A_B: f32 = 0.0047;
/// Scale parameter `b` of the red-green CSF, a single Gaussian term.
const CSF_RG_B: f32 = 0.0053;
/// Blue-yellow CSF: the sum of two Gaussian terms `(a, b)`.
const CSF_BY: [(f32, f32); 2] = [(34.1, 0.04), (13.5, 0.025)];
/// The widest scale parameter among all CSF terms; sets the filter radius.
const CSF_MAX_B: f32 = 0.04;

/// Spatial profile of one CSF term `a * sqrt(pi / b) * exp(-pi^2 r^2 / b)`
/// without its constant factor, with `r` in degrees.
fn csf_profile(b: f32, degrees: f32) -> f32 {
    (-PI * PI * degrees * degrees / b).exp()
}

/// A YCxCz image split into its three channels.
pub(super) struct Opponent {
    /// Achromatic channel (CIE-L*-like but linear).
    pub y: Plane,
    /// Red-green channel.
    pub cx: Plane,
    /// Blue-yellow channel.
    pub cz: Plane,
}

/// The separable 1-D filters approximating the human contrast sensitivity
/// for a given viewing distance.
pub(super) struct CsfFilters {
    achromatic: Vec<f32>,
    red_green: Vec<f32>,
    /// One 1-D kernel per blue-yellow term, each to be applied in both
    /// directions; their sum is the normalised 2-D filter.
    blue_yellow: [Vec<f32>; 2],
}

impl CsfFilters {
    /// Builds the filters for `pixels_per_degree`.
    ///
    /// Single-Gaussian filters are normalised to unit sum per axis. The
    /// blue-yellow filter is a sum of two Gaussians, so each term `k` is
    /// scaled by `sqrt(c_k / S)` per axis, where `c_k = a_k sqrt(pi / b_k)`
    /// and `S` is the sum of the full 2-D filter: the result equals the
    /// normalised 2-D filter exactly.
    pub fn new(pixels_per_degree: f32) -> Self {
        let radius = (3.0 * (CSF_MAX_B / (2.0 * PI * PI)).sqrt() * pixels_per_degree).ceil();
        let radius = radius as usize;
        let degrees_per_pixel = 1.0 / pixels_per_degree;
        let profile = |b: f32| kernel(radius, |i| csf_profile(b, i * degrees_per_pixel));
        let by_terms = CSF_BY.map(|(a, b)| (a * (PI / b).sqrt(), profile(b)));
        let total: f32 = by_terms
            .iter()
            .map(|(c, k)| {
                let s: f32 = k.iter().sum();
                c * s * s
            })
            .sum();
        let blue_yellow = by_terms.map(|(c, k)| {
            let scale = (c / total).sqrt();
            k.into_iter().map(|w| w * scale).collect()
        });
        Self {
            achromatic: normalized(profile(CSF_A_B)),
            red_green: normalized(profile(CSF_RG_B)),
            blue_yellow,
        }
    }

    /// Filters each opponent channel with its CSF.
    pub fn apply(&self, image: &Opponent) -> Opponent {
        let [by0, by1] = &self.blue_yellow;
        let cz0 = image.cz.filter(by0, by0);
        let cz1 = image.cz.filter(by1, by1);
        Opponent {
            y: image.y.filter(&self.achromatic, &self.achromatic),
            cx: image.cx.filter(&self.red_green, &self.red_green),
            cz: cz0.zip_map(&cz1, |a, b| a + b),
        }
    }
}

/// The largest compressed HyAB distance between two displayable colours,
/// attained between pure green and pure blue.
fn max_color_error() -> f32 {
    let green = linear_rgb_to_hunt_lab([0.0, 1.0, 0.0]);
    let blue = linear_rgb_to_hunt_lab([0.0, 0.0, 1.0]);
    hyab(green, blue).powf(QC)
}

/// The Hunt-adjusted L*a*b* colours of a CSF-filtered image: its filtered colours brought back to
/// linear RGB and clamped to the unit cube (what [`color_difference`] compares; a reference's are
/// computed once).
pub(super) fn hunt_lab(image: &Opponent) -> Vec<[f32; 3]> {
    (0..image.y.data.len())
        .into_par_iter()
        .map(|i| {
            let rgb = ycxcz_to_linear_rgb([image.y.data[i], image.cx.data[i], image.cz.data[i]]);
            linear_rgb_to_hunt_lab(rgb.map(|v| v.clamp(0.0, 1.0)))
        })
        .collect()
}

/// Per-pixel colour error in `[0, 1]` between the [`hunt_lab`] colours of two CSF-filtered
/// images: HyAB, compressed with the exponent 0.7, and remapped piecewise-linearly so that errors
/// up to 40 % of the maximum fill `[0, 0.95]` and the rest `(0.95, 1]`.
pub(super) fn color_difference(reference: &[[f32; 3]], test: &[[f32; 3]]) -> Vec<f32> {
    let cmax = max_color_error();
    let knee = PC * cmax;
    reference
        .par_iter()
        .zip(test)
        .map(|(&r, &t)| {
            let error = hyab(r, t).powf(QC);
            if error < knee {
                error * PT / knee
            } else {
                PT + (error - knee) / (cmax - knee) * (1.0 - PT)
            }
        })
        .collect()
}
