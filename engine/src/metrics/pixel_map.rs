//! A per-pixel measure of a sequence against its reference, and its share by the reference's
//! brightness: where a method flickers ([`instability_map`](super::instability_map)) or differs
//! ([`flip_map`](super::flip_map)).

use crate::capture::ImageData;

/// Per pixel, a measure of a test sequence against its reference, and the reference's brightness.
#[derive(Debug, Clone, PartialEq)]
pub struct PixelMap {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Per pixel (row-major), the measure; the mean over the pixels is the sequence's.
    pub values: Vec<f64>,
    /// Per pixel, the reference's luminance averaged over the frames, divided by its mean over
    /// the pixels and frames.
    pub brightness: Vec<f64>,
}

/// One brightness band of [`PixelMap::by_brightness`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BrightnessBand {
    /// The band holds the pixels whose brightness (relative to the mean) is at least this...
    pub from: f64,
    /// ...and below this.
    pub to: f64,
    /// The share of the pixels in the band.
    pub pixels: f64,
    /// The share of the measure's sum from them (the shares sum to 1; all 0 where the sum is).
    pub share: f64,
    /// The measure's mean over them (0 for no pixels).
    pub mean: f64,
    /// The reference's brightness averaged over them (0 for no pixels).
    pub brightness: f64,
}

impl PixelMap {
    /// The map of `values` (per pixel of `reference`'s size), its brightness from `luminances`
    /// (the reference sequence's, per frame and pixel) relative to their `mean`.
    pub(super) fn of_reference(
        reference: &ImageData,
        values: Vec<f64>,
        luminances: &[Vec<f64>],
        mean: f64,
    ) -> Self {
        let frames = luminances.len().max(1) as f64;
        let brightness = (0..values.len())
            .map(|i| luminances.iter().map(|l| l[i]).sum::<f64>() / frames / mean)
            .collect();
        Self {
            width: reference.width,
            height: reference.height,
            values,
            brightness,
        }
    }

    /// The mean over the pixels: the sequence's measure (up to rounding).
    pub fn mean(&self) -> f64 {
        self.values.iter().sum::<f64>() / self.values.len().max(1) as f64
    }

    /// The shares of pixels and of the measure per brightness band, the bands split at `edges`
    /// (increasing; below the first, between each two, from the last up).
    pub fn by_brightness(&self, edges: &[f64]) -> Vec<BrightnessBand> {
        let bounds: Vec<f64> = std::iter::once(f64::NEG_INFINITY)
            .chain(edges.iter().copied())
            .chain(std::iter::once(f64::INFINITY))
            .collect();
        let total = self.values.iter().sum::<f64>();
        let count = self.values.len().max(1) as f64;
        bounds
            .windows(2)
            .map(|b| {
                let (pixels, sum, light) = self
                    .brightness
                    .iter()
                    .zip(&self.values)
                    .filter(|(&light, _)| light >= b[0] && light < b[1])
                    .fold((0.0, 0.0, 0.0), |(n, sum, lights), (&light, &v)| {
                        (n + 1.0, sum + v, lights + light)
                    });
                let per_pixel = |x: f64| if pixels > 0.0 { x / pixels } else { 0.0 };
                BrightnessBand {
                    from: b[0].max(0.0),
                    to: b[1],
                    pixels: pixels / count,
                    share: if total > 0.0 { sum / total } else { 0.0 },
                    mean: per_pixel(sum),
                    brightness: per_pixel(light),
                }
            })
            .collect()
    }
}

/// A one-row image of grey pixels of `values`, for the maps' tests.
#[cfg(test)]
pub(super) fn grey_row(values: &[f32]) -> ImageData {
    let mut image = ImageData::new(values.len() as u32, 1);
    for (p, &v) in image.pixels.iter_mut().zip(values) {
        *p = [v, v, v, 1.0];
    }
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_share_the_measure_by_brightness() {
        let map = PixelMap {
            width: 3,
            height: 1,
            values: vec![0.0, 0.0, 0.2],
            brightness: vec![0.1, 0.9, 2.0],
        };
        let bands = map.by_brightness(&[0.5, 1.5]);
        let shares: Vec<(f64, f64)> = bands.iter().map(|b| (b.pixels, b.share)).collect();
        let third = 1.0 / 3.0;
        assert_eq!(shares, [(third, 0.0), (third, 0.0), (third, 1.0)]);
        let means: Vec<(f64, f64)> = bands.iter().map(|b| (b.mean, b.brightness)).collect();
        assert_eq!(means, [(0.0, 0.1), (0.0, 0.9), (0.2, 2.0)]);
        assert_eq!((bands[0].from, bands[2].to), (0.0, f64::INFINITY));
        assert!((map.mean() - 0.2 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn brightness_is_the_mean_over_frames_relative_to_the_whole_mean() {
        let reference = ImageData::new(2, 1);
        let map = PixelMap::of_reference(
            &reference,
            vec![0.0, 1.0],
            &[vec![1.0, 3.0], vec![3.0, 5.0]],
            2.0,
        );
        assert_eq!((map.width, map.height), (2, 1));
        assert_eq!(map.brightness, [1.0, 2.0]);
    }
}
