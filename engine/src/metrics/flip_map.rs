//! Where a sequence differs from its reference as a viewer sees it: FLIP per pixel, averaged
//! over the frames, as a [`PixelMap`].

use rayon::prelude::*;

use super::pixel_map::PixelMap;
use super::temporal::{reference_luminance, ReferenceLuminance};
use super::{FlipReference, MetricsError, DEFAULT_PIXELS_PER_DEGREE};
use crate::capture::{ImageData, PngEncoding};

/// The per-pixel FLIP of `test_frames` against `reference_frames`, both display-mapped by
/// `display` (as [`evaluate_sequence`](super::evaluate_sequence) compares them), averaged over
/// the frames: the map's mean is the sequence's mean FLIP. The same requirements as
/// [`temporal_instability`](super::temporal_instability) (the brightness is measured alike).
pub fn flip_map(
    test_frames: &[ImageData],
    reference_frames: &[ImageData],
    display: &PngEncoding,
) -> Result<PixelMap, MetricsError> {
    let ReferenceLuminance {
        frames: ref_lum,
        mean: ref_mean,
    } = reference_luminance(test_frames, reference_frames)?;
    let per_frame = test_frames
        .par_iter()
        .zip(reference_frames)
        .map(|(test, reference)| {
            FlipReference::new(&display.tone_map(reference), DEFAULT_PIXELS_PER_DEGREE)?
                .compare(&display.tone_map(test))
                .map(|flip| flip.error_map)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let frames = per_frame.len() as f64;
    let first = &reference_frames[0];
    let values = (0..first.pixels.len())
        .into_par_iter()
        .map(|i| per_frame.iter().map(|m| f64::from(m[i])).sum::<f64>() / frames)
        .collect();
    Ok(PixelMap::of_reference(first, values, &ref_lum, ref_mean))
}

#[cfg(test)]
mod tests {
    use super::super::evaluate_sequence;
    use super::*;
    use crate::capture::ToneCurve;

    fn frame(width: u32, f: impl Fn(u32, u32) -> f32) -> ImageData {
        let mut image = ImageData::new(width, width);
        for (i, p) in image.pixels.iter_mut().enumerate() {
            let v = f(i as u32 % width, i as u32 / width);
            *p = [v, v, v, 1.0];
        }
        image
    }

    #[test]
    fn the_map_locates_the_difference_and_averages_to_the_sequences_flip() {
        let display = PngEncoding {
            tone: ToneCurve::Aces,
            ..PngEncoding::default()
        };
        let reference = vec![frame(32, |_, _| 0.5); 2];
        // The second frame is brighter in its top-left 4x4 block only.
        let test = vec![
            frame(32, |_, _| 0.5),
            frame(32, |x, y| if x < 4 && y < 4 { 3.0 } else { 0.5 }),
        ];
        let map = flip_map(&test, &reference, &display).unwrap();
        assert_eq!((map.width, map.height), (32, 32));
        let (corner, far) = (map.values[0], map.values[31 * 32 + 31]);
        assert!(corner > 0.1 && far < 1e-6, "corner {corner}, far {far}");
        let whole = evaluate_sequence(&test, &reference, &display)
            .unwrap()
            .mean
            .flip;
        assert!(
            (map.mean() - whole).abs() < 1e-6,
            "{} vs {whole}",
            map.mean()
        );
        assert!(map.brightness.iter().all(|&b| (b - 1.0).abs() < 1e-9));
    }

    #[test]
    fn the_map_refuses_what_temporal_instability_refuses() {
        let one = vec![frame(4, |_, _| 1.0)];
        assert!(matches!(
            flip_map(&one, &one, &PngEncoding::default()),
            Err(MetricsError::TooFewFrames { count: 1 })
        ));
    }
}
