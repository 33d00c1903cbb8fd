//! Where a sequence flickers: [`temporal_instability`](super::temporal_instability) per pixel,
//! and its share by the reference's brightness.

use rayon::prelude::*;

use super::temporal::{luminances, Luminances};
use super::MetricsError;
use crate::capture::ImageData;

/// Per pixel, the temporal instability and the reference's brightness.
#[derive(Debug, Clone, PartialEq)]
pub struct InstabilityMap {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Per pixel (row-major), `|(L_test[i+1] - L_test[i]) - (L_ref[i+1] - L_ref[i])|` averaged
    /// over the frame pairs and divided by the reference sequence's mean luminance: the mean over
    /// the pixels is the sequence's temporal instability.
    pub instability: Vec<f64>,
    /// Per pixel, the reference's luminance averaged over the frames, divided by the same mean.
    pub brightness: Vec<f64>,
}

/// One brightness band of [`InstabilityMap::by_brightness`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BrightnessBand {
    /// The band holds the pixels whose brightness (relative to the mean) is at least this...
    pub from: f64,
    /// ...and below this.
    pub to: f64,
    /// The share of the pixels in the band.
    pub pixels: f64,
    /// The share of the temporal instability from them (the shares sum to 1).
    pub instability: f64,
}

/// The per-pixel temporal instability of `test_frames` against `reference_frames`, with the same
/// requirements as [`temporal_instability`](super::temporal_instability).
pub fn instability_map(
    test_frames: &[ImageData],
    reference_frames: &[ImageData],
) -> Result<InstabilityMap, MetricsError> {
    let Luminances {
        test: test_lum,
        reference: ref_lum,
        reference_mean: ref_mean,
    } = luminances(test_frames, reference_frames)?;
    let pairs = (test_lum.len() - 1) as f64;
    let frames = ref_lum.len() as f64;
    let first = &reference_frames[0];
    let (instability, brightness) = (0..first.pixels.len())
        .into_par_iter()
        .map(|i| {
            let change: f64 = test_lum
                .windows(2)
                .zip(ref_lum.windows(2))
                .map(|(t, r)| ((t[1][i] - t[0][i]) - (r[1][i] - r[0][i])).abs())
                .sum();
            let light: f64 = ref_lum.iter().map(|r| r[i]).sum();
            (change / pairs / ref_mean, light / frames / ref_mean)
        })
        .unzip();
    Ok(InstabilityMap {
        width: first.width,
        height: first.height,
        instability,
        brightness,
    })
}

impl InstabilityMap {
    /// The mean over the pixels: the sequence's temporal instability (up to rounding).
    pub fn mean(&self) -> f64 {
        self.instability.iter().sum::<f64>() / self.instability.len().max(1) as f64
    }

    /// The shares of pixels and of instability per brightness band, the bands split at `edges`
    /// (increasing; below the first, between each two, from the last up).
    pub fn by_brightness(&self, edges: &[f64]) -> Vec<BrightnessBand> {
        let bounds: Vec<f64> = std::iter::once(f64::NEG_INFINITY)
            .chain(edges.iter().copied())
            .chain(std::iter::once(f64::INFINITY))
            .collect();
        let total = self.instability.iter().sum::<f64>();
        let count = self.instability.len().max(1) as f64;
        bounds
            .windows(2)
            .map(|b| {
                let (pixels, instability) = self
                    .brightness
                    .iter()
                    .zip(&self.instability)
                    .filter(|(&light, _)| light >= b[0] && light < b[1])
                    .fold((0.0, 0.0), |(n, sum), (_, &v)| (n + 1.0, sum + v));
                BrightnessBand {
                    from: b[0].max(0.0),
                    to: b[1],
                    pixels: pixels / count,
                    instability: if total > 0.0 {
                        instability / total
                    } else {
                        0.0
                    },
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::temporal_instability;
    use super::*;

    fn frame(values: &[f32]) -> ImageData {
        let mut image = ImageData::new(values.len() as u32, 1);
        for (p, &v) in image.pixels.iter_mut().zip(values) {
            *p = [v, v, v, 1.0];
        }
        image
    }

    #[test]
    fn the_map_locates_the_flicker_and_averages_to_the_instability() {
        // A still reference: a dark pixel, a mid one and a bright one (mean 1). The test flickers
        // by 0.2 on the bright pixel only.
        let reference = vec![frame(&[0.1, 0.9, 2.0]); 3];
        let test = vec![
            frame(&[0.1, 0.9, 2.0]),
            frame(&[0.1, 0.9, 2.2]),
            frame(&[0.1, 0.9, 2.0]),
        ];
        let map = instability_map(&test, &reference).unwrap();
        assert_eq!((map.width, map.height), (3, 1));
        assert!(map.instability[0].abs() < 1e-9 && map.instability[1].abs() < 1e-9);
        assert!(
            (map.instability[2] - 0.2).abs() < 1e-6,
            "{:?}",
            map.instability
        );
        assert!((map.brightness[2] - 2.0).abs() < 1e-6);
        let whole = temporal_instability(&test, &reference).unwrap().mean;
        assert!(
            (map.mean() - whole).abs() < 1e-12,
            "{} vs {whole}",
            map.mean()
        );
        let bands = map.by_brightness(&[0.5, 1.5]);
        let shares: Vec<(f64, f64)> = bands.iter().map(|b| (b.pixels, b.instability)).collect();
        let third = 1.0 / 3.0;
        assert_eq!(shares, [(third, 0.0), (third, 0.0), (third, 1.0)]);
        assert_eq!((bands[0].from, bands[2].to), (0.0, f64::INFINITY));
    }

    #[test]
    fn the_map_refuses_what_temporal_instability_refuses() {
        let one = vec![frame(&[1.0])];
        assert!(matches!(
            instability_map(&one, &one),
            Err(MetricsError::TooFewFrames { count: 1 })
        ));
        let black = vec![frame(&[0.0]); 2];
        assert!(matches!(
            instability_map(&black, &black),
            Err(MetricsError::DegenerateReference { .. })
        ));
    }
}
