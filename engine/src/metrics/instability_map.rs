//! Where a sequence flickers: [`temporal_instability`](super::temporal_instability) per pixel,
//! as a [`PixelMap`].

use rayon::prelude::*;

use super::pixel_map::PixelMap;
use super::temporal::{luminances, Luminances, ReferenceLuminance};
use super::MetricsError;
use crate::capture::ImageData;

/// The per-pixel temporal instability of `test_frames` against `reference_frames`, with the same
/// requirements as [`temporal_instability`](super::temporal_instability): per pixel,
/// `|(L_test[i+1] - L_test[i]) - (L_ref[i+1] - L_ref[i])|` averaged over the frame pairs and
/// divided by the reference sequence's mean luminance, so that the map's mean is the sequence's
/// temporal instability.
pub fn instability_map(
    test_frames: &[ImageData],
    reference_frames: &[ImageData],
) -> Result<PixelMap, MetricsError> {
    let Luminances {
        test: test_lum,
        reference:
            ReferenceLuminance {
                frames: ref_lum,
                mean: ref_mean,
            },
    } = luminances(test_frames, reference_frames)?;
    let pairs = (test_lum.len() - 1) as f64;
    let first = &reference_frames[0];
    let values = (0..first.pixels.len())
        .into_par_iter()
        .map(|i| {
            let change: f64 = test_lum
                .windows(2)
                .zip(ref_lum.windows(2))
                .map(|(t, r)| ((t[1][i] - t[0][i]) - (r[1][i] - r[0][i])).abs())
                .sum();
            change / pairs / ref_mean
        })
        .collect();
    Ok(PixelMap::of_reference(first, values, &ref_lum, ref_mean))
}

#[cfg(test)]
mod tests {
    use super::super::pixel_map::grey_row as frame;
    use super::super::temporal_instability;
    use super::*;

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
        assert!(map.values[0].abs() < 1e-9 && map.values[1].abs() < 1e-9);
        assert!((map.values[2] - 0.2).abs() < 1e-6, "{:?}", map.values);
        assert!((map.brightness[2] - 2.0).abs() < 1e-6);
        let whole = temporal_instability(&test, &reference).unwrap().mean;
        assert!(
            (map.mean() - whole).abs() < 1e-12,
            "{} vs {whole}",
            map.mean()
        );
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
