//! How much of the reference's light a sequence keeps: its luminance per pixel averaged over the
//! frames, as a [`PixelMap`] on the reference's brightness scale, so that a brightness band's
//! [`BrightnessBand::mean`](super::BrightnessBand::mean) over its
//! [`brightness`](super::BrightnessBand::brightness) is the share of the band's light the sequence
//! has (below 1 where a denoiser clamps away a caustic that rare paths bring).

use rayon::prelude::*;

use super::pixel_map::PixelMap;
use super::temporal::luminances;
use super::MetricsError;
use crate::capture::ImageData;

/// Per pixel, the luminance of `test_frames` averaged over the frames and divided by the mean
/// luminance of `reference_frames` (over pixels and frames), whose per-pixel means make the map's
/// brightness; the same requirements as [`temporal_instability`](super::temporal_instability).
pub fn light_map(
    test_frames: &[ImageData],
    reference_frames: &[ImageData],
) -> Result<PixelMap, MetricsError> {
    let lum = luminances(test_frames, reference_frames)?;
    let (frames, mean) = (lum.test.len() as f64, lum.reference.mean);
    let values = (0..reference_frames[0].pixels.len())
        .into_par_iter()
        .map(|i| lum.test.iter().map(|t| t[i]).sum::<f64>() / frames / mean)
        .collect();
    Ok(PixelMap::of_reference(
        &reference_frames[0],
        values,
        &lum.reference.frames,
        mean,
    ))
}

#[cfg(test)]
mod tests {
    use super::super::pixel_map::grey_row as frame;
    use super::*;

    #[test]
    fn bands_compare_the_light_kept_with_the_reference() {
        // A still reference, a dim pixel and a bright one (mean 2); the test keeps the dim pixel
        // and half of the bright one on average (1.0 and 2.0 over two frames).
        let reference = [frame(&[1.0, 3.0]), frame(&[1.0, 3.0])];
        let test = [frame(&[1.0, 1.0]), frame(&[1.0, 2.0])];
        let map = light_map(&test, &reference).unwrap();
        let bands = map.by_brightness(&[1.0]);
        let kept: Vec<f64> = bands.iter().map(|b| b.mean / b.brightness).collect();
        assert_eq!(kept, [1.0, 0.5]);
        assert!((map.mean() - 1.25 / 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_sequence_of_another_size_is_an_error() {
        let reference = [frame(&[1.0, 3.0]), frame(&[1.0, 3.0])];
        let test = [frame(&[1.0]), frame(&[1.0])];
        assert!(light_map(&test, &reference).is_err());
    }
}
