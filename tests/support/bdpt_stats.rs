//! Statistics for comparing Monte Carlo estimates of one image (shared by the BDPT tests).

use lucid_engine::capture::ImageData;

/// Per-channel mean of an image.
pub fn mean(image: &ImageData) -> [f64; 3] {
    let mut sum = [0.0f64; 3];
    for p in &image.pixels {
        for (s, v) in sum.iter_mut().zip(p) {
            *s += f64::from(*v);
        }
    }
    sum.map(|s| s / image.pixels.len() as f64)
}

/// The noise of an estimator from two renders with independent seeds, relative to its image: the
/// mean squared difference of their channels over twice the squared mean of the pair's channels
/// (the variance of one render over its squared mean, for the image as a whole).
pub fn relative_noise(renders: [&ImageData; 2]) -> f64 {
    let (mut squared_difference, mut sum) = (0.0f64, 0.0f64);
    let mut count = 0.0f64;
    for (a, b) in renders[0].pixels.iter().zip(&renders[1].pixels) {
        for c in 0..3 {
            let (a, b) = (f64::from(a[c]), f64::from(b[c]));
            squared_difference += (a - b) * (a - b);
            sum += 0.5 * (a + b);
            count += 1.0;
        }
    }
    let mean = sum / count.max(1.0);
    squared_difference / count.max(1.0) / (2.0 * mean * mean).max(1e-30)
}

/// The pixelwise average of two images.
fn average(a: &ImageData, b: &ImageData) -> ImageData {
    let mut out = a.clone();
    for (o, q) in out.pixels.iter_mut().zip(&b.pixels) {
        for c in 0..3 {
            o[c] = 0.5 * (o[c] + q[c]);
        }
    }
    out
}

/// Two estimators of one image, each rendered twice with independent seeds.
#[derive(Debug)]
pub struct Comparison {
    /// Channel means of estimator a (both renders averaged).
    pub mean_a: [f64; 3],
    /// Channel means of estimator b.
    pub mean_b: [f64; 3],
    /// Standard deviation of the difference of the channel means, from the pairs' noise.
    pub mean_sigma: [f64; 3],
    /// Relative MSE between the two averaged estimates.
    pub rel_mse: f64,
    /// The relative MSE their noise alone explains: each averaged estimate's variance is
    /// (x1 - x2)^2 / 4 per pixel.
    pub expected_rel_mse: f64,
}

impl Comparison {
    /// Compares estimator a (renders a1, a2) with estimator b (b1, b2).
    pub fn new(a: [&ImageData; 2], b: [&ImageData; 2]) -> Self {
        let (ma, mb) = (average(a[0], a[1]), average(b[0], b[1]));
        let reference = average(&ma, &mb);
        let floor = 0.01 * mean_luminance(&reference).powi(2);
        let n = reference.pixels.len() as f64;
        let mut observed = 0.0;
        let mut expected = 0.0;
        let mut mean_var = [0.0f64; 3];
        for i in 0..reference.pixels.len() {
            let denom = luminance(&reference.pixels[i]).powi(2) + floor;
            for (c, var) in mean_var.iter_mut().enumerate() {
                let d = f64::from(ma.pixels[i][c] - mb.pixels[i][c]);
                let da = f64::from(a[0].pixels[i][c] - a[1].pixels[i][c]);
                let db = f64::from(b[0].pixels[i][c] - b[1].pixels[i][c]);
                let noise = 0.25 * (da * da + db * db);
                observed += d * d / denom;
                expected += noise / denom;
                *var += noise / (n * n);
            }
        }
        Self {
            mean_a: mean(&ma),
            mean_b: mean(&mb),
            mean_sigma: mean_var.map(f64::sqrt),
            rel_mse: observed / n,
            expected_rel_mse: expected / n,
        }
    }

    /// Observed over expected relative MSE: about 1 when both estimate the same image.
    pub fn ratio(&self) -> f64 {
        self.rel_mse / self.expected_rel_mse
    }

    /// Largest relative difference of the channel means.
    pub fn mean_difference(&self) -> f64 {
        (0..3)
            .map(|c| (self.mean_a[c] - self.mean_b[c]).abs() / self.mean_a[c].max(1e-9))
            .fold(0.0, f64::max)
    }

    /// Largest difference of the channel means in standard deviations of their noise.
    pub fn mean_z(&self) -> f64 {
        (0..3)
            .map(|c| (self.mean_a[c] - self.mean_b[c]).abs() / self.mean_sigma[c].max(1e-12))
            .fold(0.0, f64::max)
    }

    /// Prints the comparison of `name`'s two estimators.
    pub fn report(&self, name: &str) {
        eprintln!(
            "{name}: {self:?}\n  mean difference {:.2}% ({:.1} sigma), relMSE ratio {:.3}",
            100.0 * self.mean_difference(),
            self.mean_z(),
            self.ratio()
        );
    }

    /// Panics unless the two estimators of `name` converge to one image: channel means within 2%
    /// and 4 standard deviations of their noise, and a relative MSE between them at most
    /// `max_ratio` times what their noise explains.
    pub fn assert_converged(&self, name: &str, max_ratio: f64) {
        assert!(
            self.mean_difference() < 0.02 && self.mean_z() < 4.0,
            "{name}: channel means differ: {:?} vs {:?}",
            self.mean_a,
            self.mean_b
        );
        assert!(
            self.ratio() < max_ratio,
            "{name}: relative MSE {:.4} between the estimates, noise explains {:.4}",
            self.rel_mse,
            self.expected_rel_mse
        );
    }
}

fn luminance(p: &[f32; 4]) -> f64 {
    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
}

fn mean_luminance(image: &ImageData) -> f64 {
    image.pixels.iter().map(luminance).sum::<f64>() / image.pixels.len() as f64
}
