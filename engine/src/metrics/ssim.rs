//! Structural similarity (Wang et al. 2004) and its DSSIM transform.

use super::check::{check_pair, check_parameter};
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
/// sigma 1.5, `K1 = 0.01`, `K2 = 0.03`, dynamic range 1, population
/// (not sample) covariances, the mean taken over the pixels whose window
/// lies inside the image (those at least 5 pixels from the border), as Wang
/// et al.'s code and scikit-image's `structural_similarity(...,
/// gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
/// data_range=1)` take it (`tests/metrics_reference/` checks the agreement).
/// Images narrower or lower than the window (11 pixels) are an error.
///
/// Values are clamped to `[0, 1]` (NaN counts as 0) before comparison, so
/// the inputs should be display-referred: for linear HDR frames, compare
/// [`PngEncoding::to_display`](crate::capture::PngEncoding::to_display) of
/// both images. Identical images give exactly 1.
pub fn ssim(test: &ImageData, reference: &ImageData, mode: SsimMode) -> Result<f64, MetricsError> {
    check_pair(test, reference)?;
    let side = 2 * WINDOW_RADIUS as u32 + 1;
    check_parameter(
        "image size",
        f64::from(test.width.min(test.height)),
        test.width >= side && test.height >= side,
        "SSIM needs images of at least 11x11 pixels (its window)",
    )?;
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

/// Mean of the SSIM map of two equally sized planes over the pixels whose window lies inside.
fn plane_ssim(x: &Plane, y: &Plane, window: &[f32]) -> f64 {
    let blur = |p: &Plane| p.filter(window, window);
    let mu_x = blur(x);
    let mu_y = blur(y);
    let xx = blur(&x.zip_map(x, |a, b| a * b));
    let yy = blur(&y.zip_map(y, |a, b| a * b));
    let xy = blur(&x.zip_map(y, |a, b| a * b));
    let r = WINDOW_RADIUS;
    let (w, h) = (x.width, x.height);
    let inside = (r..h - r).flat_map(|row| (r..w - r).map(move |col| row * w + col));
    let count = (w - 2 * r) * (h - 2 * r);
    let sum: f64 = inside
        .map(|i| {
            let (mx, my) = (f64::from(mu_x.data[i]), f64::from(mu_y.data[i]));
            let var_x = f64::from(xx.data[i]) - mx * mx;
            let var_y = f64::from(yy.data[i]) - my * my;
            let cov = f64::from(xy.data[i]) - mx * my;
            ((2.0 * mx * my + C1) * (2.0 * cov + C2))
                / ((mx * mx + my * my + C1) * (var_x + var_y + C2))
        })
        .sum();
    sum / count as f64
}
