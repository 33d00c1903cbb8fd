//! A single-channel float image and separable filtering over it.

use rayon::prelude::*;

use crate::capture::ImageData;

/// One channel of an image, row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Plane {
    /// Width in samples.
    pub width: usize,
    /// Height in samples.
    pub height: usize,
    /// `width * height` samples.
    pub data: Vec<f32>,
}

impl Plane {
    /// Extracts one value per pixel of `image` with `f`.
    pub fn from_image(image: &ImageData, f: impl Fn([f32; 4]) -> f32 + Sync) -> Self {
        Self {
            width: image.width as usize,
            height: image.height as usize,
            data: image.pixels.par_iter().map(|&p| f(p)).collect(),
        }
    }

    /// Applies `f` to every sample.
    pub fn map(&self, f: impl Fn(f32) -> f32 + Sync) -> Plane {
        Plane {
            width: self.width,
            height: self.height,
            data: self.data.par_iter().map(|&v| f(v)).collect(),
        }
    }

    /// Combines two planes of equal size sample by sample.
    pub fn zip_map(&self, other: &Plane, f: impl Fn(f32, f32) -> f32 + Sync) -> Plane {
        Plane {
            width: self.width,
            height: self.height,
            data: self
                .data
                .par_iter()
                .zip(&other.data)
                .map(|(&a, &b)| f(a, b))
                .collect(),
        }
    }

    /// Correlates the plane with the separable kernel `horizontal ⊗
    /// vertical` (both of odd length, centred), replicating edge samples
    /// outside the plane.
    pub fn filter(&self, horizontal: &[f32], vertical: &[f32]) -> Plane {
        let rows = self.filter_rows(horizontal);
        rows.filter_columns(vertical)
    }

    /// Correlates each row with `kernel` (odd length, centred), replicating edge samples.
    pub fn filter_rows(&self, kernel: &[f32]) -> Plane {
        let radius = kernel.len() / 2;
        let width = self.width.max(1);
        let mut data = vec![0.0; self.data.len()];
        data.par_chunks_mut(width)
            .zip(self.data.par_chunks(width))
            .for_each(|(out, row)| filter_row(row, kernel, radius, out));
        Plane {
            width: self.width,
            height: self.height,
            data,
        }
    }

    /// Correlates each column with `kernel` (odd length, centred), replicating edge samples.
    pub fn filter_columns(&self, kernel: &[f32]) -> Plane {
        let radius = (kernel.len() / 2) as isize;
        let last = self.height as isize - 1;
        let width = self.width.max(1);
        let mut data = vec![0.0; self.data.len()];
        data.par_chunks_mut(width).enumerate().for_each(|(y, out)| {
            for (k, w) in kernel.iter().enumerate() {
                let src = (y as isize + k as isize - radius).clamp(0, last) as usize;
                let row = &self.data[src * width..(src + 1) * width];
                for (o, v) in out.iter_mut().zip(row) {
                    *o += w * v;
                }
            }
        });
        Plane {
            width: self.width,
            height: self.height,
            data,
        }
    }
}

/// Correlates one row with `kernel` (centred, `radius` taps each side), replicating the edge
/// samples; pixels whose window lies inside the row are summed tap by tap over the whole run (a
/// loop the compiler vectorises), the few near the ends one by one.
fn filter_row(row: &[f32], kernel: &[f32], radius: usize, out: &mut [f32]) {
    let n = row.len();
    let last = n as isize - 1;
    let clamped = |x: usize| -> f32 {
        kernel
            .iter()
            .enumerate()
            .map(|(k, w)| {
                let src = (x as isize + k as isize - radius as isize).clamp(0, last);
                w * row[src as usize]
            })
            .sum()
    };
    if n <= 2 * radius {
        for (x, o) in out.iter_mut().enumerate() {
            *o = clamped(x);
        }
        return;
    }
    let inside = &mut out[radius..n - radius];
    inside.fill(0.0);
    for (k, w) in kernel.iter().enumerate() {
        for (o, v) in inside.iter_mut().zip(&row[k..k + n - 2 * radius]) {
            *o += w * v;
        }
    }
    for x in (0..radius).chain(n - radius..n) {
        out[x] = clamped(x);
    }
}

/// Clamps a sample to the display range `[0, 1]`, NaN to 0: how the
/// perceptual metrics read pixel values.
pub(super) fn clamp_unit(v: f32) -> f32 {
    if v.is_nan() {
        0.0
    } else {
        v.clamp(0.0, 1.0)
    }
}

/// A centred 1-D kernel of `2 * radius + 1` taps, `f(offset)` at each tap.
pub(super) fn kernel(radius: usize, f: impl Fn(f32) -> f32) -> Vec<f32> {
    let r = radius as isize;
    (-r..=r).map(|i| f(i as f32)).collect()
}

/// Scales `kernel` so its taps sum to 1.
pub(super) fn normalized(kernel: Vec<f32>) -> Vec<f32> {
    let sum: f32 = kernel.iter().sum();
    kernel.into_iter().map(|w| w / sum).collect()
}
