//! Structural similarity (Wang et al. 2004) and its DSSIM transform.

use super::check::{check_image, check_pair, check_parameter, check_size};
use super::plane::{clamp_unit, kernel, normalized, Plane};
use super::sum::ordered_sum;
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
    SsimReference::new(reference, mode)?.compare(test)
}

/// A reference image prepared for [`ssim`] against many test images: its signal planes with
/// their windowed means and mean squares, computed once.
#[derive(Debug, Clone)]
pub struct SsimReference {
    mode: SsimMode,
    window: Vec<f32>,
    /// Per compared plane: the signal, its windowed mean and its windowed mean square.
    planes: Vec<[Plane; 3]>,
    size: (u32, u32),
}

impl SsimReference {
    /// Prepares `reference` (at least 11x11 pixels) for comparisons in `mode`.
    pub fn new(reference: &ImageData, mode: SsimMode) -> Result<Self, MetricsError> {
        check_image(reference)?;
        let side = 2 * WINDOW_RADIUS as u32 + 1;
        check_parameter(
            "image size",
            f64::from(reference.width.min(reference.height)),
            reference.width >= side && reference.height >= side,
            "SSIM needs images of at least 11x11 pixels (its window)",
        )?;
        let window = normalized(kernel(WINDOW_RADIUS, |x| {
            (-x * x / (2.0 * WINDOW_SIGMA * WINDOW_SIGMA)).exp()
        }));
        let planes = signals(reference, mode)
            .into_iter()
            .map(|y| {
                let mean = y.filter(&window, &window);
                let square = y.map(|v| v * v).filter(&window, &window);
                [y, mean, square]
            })
            .collect();
        Ok(Self {
            mode,
            window,
            planes,
            size: (reference.width, reference.height),
        })
    }

    /// Mean SSIM of `test` (the reference's size) against the prepared reference.
    pub fn compare(&self, test: &ImageData) -> Result<f64, MetricsError> {
        check_image(test)?;
        check_size(test, self.size)?;
        let tests = signals(test, self.mode);
        let total: f64 = tests
            .iter()
            .zip(&self.planes)
            .map(|(x, [y, mu_y, yy])| {
                let blur = |p: &Plane| p.filter(&self.window, &self.window);
                let mu_x = blur(x);
                let xx = blur(&x.map(|v| v * v));
                let xy = blur(&x.zip_map(y, |a, b| a * b));
                mean_ssim([&mu_x, mu_y, &xx, yy, &xy])
            })
            .sum();
        Ok(total / tests.len() as f64)
    }
}

/// The planes `mode` compares: the luminance of the clamped R, G, B, or each clamped channel.
fn signals(image: &ImageData, mode: SsimMode) -> Vec<Plane> {
    match mode {
        SsimMode::Luminance => vec![Plane::from_image(image, |p| {
            rec709_luminance(p.map(clamp_unit))
        })],
        SsimMode::PerChannel => (0..3)
            .map(|c| Plane::from_image(image, |p| clamp_unit(p[c])))
            .collect(),
    }
}

/// DSSIM as defined by the study the evaluation follows: `1 / ssim - 1`.
/// 0 for identical images, growing without bound as SSIM falls to 0.
pub fn dssim(ssim: f64) -> f64 {
    1.0 / ssim - 1.0
}

/// Mean of the SSIM map over the pixels whose window lies inside, from the windowed means of
/// x and y, of their squares and of their product.
fn mean_ssim([mu_x, mu_y, xx, yy, xy]: [&Plane; 5]) -> f64 {
    let r = WINDOW_RADIUS;
    let (w, h) = (mu_x.width, mu_x.height);
    let count = (w - 2 * r) * (h - 2 * r);
    let sum = ordered_sum(h - 2 * r, |row| {
        let row = row + r;
        (row * w + r..row * w + w - r)
            .map(|i| {
                let (mx, my) = (f64::from(mu_x.data[i]), f64::from(mu_y.data[i]));
                let var_x = f64::from(xx.data[i]) - mx * mx;
                let var_y = f64::from(yy.data[i]) - my * my;
                let cov = f64::from(xy.data[i]) - mx * my;
                ((2.0 * mx * my + C1) * (2.0 * cov + C2))
                    / ((mx * mx + my * my + C1) * (var_x + var_y + C2))
            })
            .sum::<f64>()
    });
    sum / count as f64
}
