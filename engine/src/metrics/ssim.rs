//! Structural similarity (Wang et al. 2004) and its DSSIM transform.

use super::check::check_pair;
use super::plane::{clamp_unit, kernel, normalized, Plane};
use super::MetricsError;
use crate::capture::{rec709_luminance, ImageData};

/// Radius of the 11-tap Gaussian window.
const WINDOW_RADIUS: usize = 5;
/// Standard deviation of the Gaussian window, in pixels.
const WINDOW_SIGMA: f32 = 1.5;
/// `(K1 L)^2` with `K1 = 0.01` and dynamic range `L = 1`.
const C1: f64 = 0.01 * 0.01;
/// `(K2 L)^2` with `K2 = 0.03` and dynamic range `L = 1`.
const C2: f64 = 0.03 * 0.03;

/// Which signal SSIM compares.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SsimMode {
    /// The Rec.709 luminance of the clamped R, G, B values.
    #[default]
    Luminance,
    /// R, G and B separately; the result is the mean of the three.
    PerChannel,
}

/// Mean SSIM of `test` against `reference`: 11x11 Gaussian window with
/// sigma 1.5, `K1 = 0.01`, `K2 = 0.03`, dynamic range 1, edge pixels
/// replicated at the borders.
///
/// Values are clamped to `[0, 1]` (NaN counts as 0) before comparison, so
/// the inputs should be display-referred: for linear HDR frames, compare
/// [`PngEncoding::to_display`](crate::capture::PngEncoding::to_display) of
/// both images. Identical images give exactly 1.
pub fn ssim(test: &ImageData, reference: &ImageData, mode: SsimMode) -> Result<f64, MetricsError> {
    check_pair(test, reference)?;
    let window = normalized(kernel(WINDOW_RADIUS, |x| {
        (-x * x / (2.0 * WINDOW_SIGMA * WINDOW_SIGMA)).exp()
    }));
    let mean = match mode {
        SsimMode::Luminance => {
            let signal = |p: [f32; 4]| rec709_luminance(p.map(clamp_unit));
            plane_ssim(
                &Plane::from_image(test, signal),
                &Plane::from_image(reference, signal),
                &window,
            )
        }
        SsimMode::PerChannel => {
            let total: f64 = (0..3)
                .map(|c| {
                    plane_ssim(
                        &Plane::from_image(test, |p| clamp_unit(p[c])),
                        &Plane::from_image(reference, |p| clamp_unit(p[c])),
                        &window,
                    )
                })
                .sum();
            total / 3.0
        }
    };
    Ok(mean)
}

/// DSSIM as defined by the study the evaluation follows: `1 / ssim - 1`.
/// 0 for identical images, growing without bound as SSIM falls to 0.
pub fn dssim(ssim: f64) -> f64 {
    1.0 / ssim - 1.0
}

/// Mean of the SSIM map of two equally sized planes.
fn plane_ssim(x: &Plane, y: &Plane, window: &[f32]) -> f64 {
    let blur = |p: &Plane| p.filter(window, window);
    let mu_x = blur(x);
    let mu_y = blur(y);
    let xx = blur(&x.zip_map(x, |a, b| a * b));
    let yy = blur(&y.zip_map(y, |a, b| a * b));
    let xy = blur(&x.zip_map(y, |a, b| a * b));
    let sum: f64 = (0..x.data.len())
        .map(|i| {
            let (mx, my) = (f64::from(mu_x.data[i]), f64::from(mu_y.data[i]));
            let var_x = f64::from(xx.data[i]) - mx * mx;
            let var_y = f64::from(yy.data[i]) - my * my;
            let cov = f64::from(xy.data[i]) - mx * my;
            ((2.0 * mx * my + C1) * (2.0 * cov + C2))
                / ((mx * mx + my * my + C1) * (var_x + var_y + C2))
        })
        .sum();
    sum / x.data.len() as f64
}
