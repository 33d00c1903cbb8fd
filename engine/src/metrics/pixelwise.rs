//! Per-pixel error statistics: means, MSE, relative MSE, PSNR, max error.

use super::check::{check_image, check_pair, check_parameter};
use super::sum::ordered_sum;
use super::MetricsError;
use crate::capture::ImageData;

/// The customary `eps` for [`rel_mse`]: keeps near-black reference pixels
/// from dominating.
pub const DEFAULT_REL_MSE_EPSILON: f64 = 1e-2;

/// Mean of each channel (R, G, B, A) over all pixels, accumulated in `f64`.
pub fn mean_per_channel(image: &ImageData) -> Result<[f64; 4], MetricsError> {
    check_image(image)?;
    let sum = image.pixels.iter().fold([0.0f64; 4], |mut acc, p| {
        for (a, &v) in acc.iter_mut().zip(p) {
            *a += f64::from(v);
        }
        acc
    });
    Ok(sum.map(|s| s / image.pixels.len() as f64))
}

/// Mean over all pixels and the R, G, B channels of `f(test, reference)`.
fn mean_rgb_of(
    test: &ImageData,
    reference: &ImageData,
    f: impl Fn(f64, f64) -> f64 + Sync,
) -> Result<f64, MetricsError> {
    check_pair(test, reference)?;
    let sum = ordered_sum(test.pixels.len(), |i| {
        let (t, r) = (test.pixels[i], reference.pixels[i]);
        (0..3)
            .map(|c| f(f64::from(t[c]), f64::from(r[c])))
            .sum::<f64>()
    });
    Ok(sum / (3 * test.pixels.len()) as f64)
}

/// Mean squared error over all pixels and the R, G, B channels.
pub fn mse(test: &ImageData, reference: &ImageData) -> Result<f64, MetricsError> {
    mean_rgb_of(test, reference, |t, r| (t - r) * (t - r))
}

/// Relative MSE: the mean over all pixels and R, G, B of
/// `(t - r)^2 / (r^2 + eps)`. `eps` must be finite and positive; use
/// [`DEFAULT_REL_MSE_EPSILON`] unless a study prescribes otherwise.
pub fn rel_mse(test: &ImageData, reference: &ImageData, eps: f64) -> Result<f64, MetricsError> {
    check_parameter("eps", eps, eps > 0.0, "must be positive")?;
    mean_rgb_of(test, reference, |t, r| (t - r) * (t - r) / (r * r + eps))
}

/// Peak signal-to-noise ratio in decibels, `10 log10(peak^2 / mse)`, for
/// signals whose full range is `peak` (1 for `[0, 1]` data). Identical images
/// give `f64::INFINITY`.
pub fn psnr(test: &ImageData, reference: &ImageData, peak: f64) -> Result<f64, MetricsError> {
    check_parameter("peak", peak, peak > 0.0, "must be positive")?;
    let error = mse(test, reference)?;
    if error == 0.0 {
        return Ok(f64::INFINITY);
    }
    Ok(10.0 * (peak * peak / error).log10())
}

/// Largest absolute difference of any R, G or B value (NaN if any
/// difference is NaN).
pub fn max_abs_error(test: &ImageData, reference: &ImageData) -> Result<f64, MetricsError> {
    check_pair(test, reference)?;
    Ok(test
        .pixels
        .iter()
        .zip(&reference.pixels)
        .flat_map(|(t, r)| (0..3).map(move |c| (f64::from(t[c]) - f64::from(r[c])).abs()))
        .fold(0.0, |max, d| if d.is_nan() || d > max { d } else { max }))
}
