//! Temporal instability (flicker) of a frame sequence against a reference
//! sequence.

use rayon::prelude::*;

use super::check::check_pair;
use super::sum::ordered_sum;
use super::MetricsError;
use crate::capture::{rec709_luminance, ImageData};

/// Result of [`temporal_instability`].
#[derive(Debug, Clone, PartialEq)]
pub struct TemporalInstability {
    /// One value per consecutive frame pair `(i, i + 1)`.
    pub per_pair: Vec<f64>,
    /// Mean of `per_pair`.
    pub mean: f64,
}

/// How much more (or differently) the test sequence changes from frame to
/// frame than the reference does.
///
/// For each consecutive pair `(i, i + 1)` and each pixel, with `L` the
/// Rec.709 luminance:
/// `|(L_test[i+1] - L_test[i]) - (L_ref[i+1] - L_ref[i])|`, averaged over
/// the pixels and divided by the mean luminance of the whole reference
/// sequence. Identical sequences give 0; a test that flickers over a static
/// reference gives its mean frame-to-frame luminance change relative to the
/// reference brightness.
///
/// All frames must have the same size, the sequences the same length (at
/// least 2), and the reference a positive mean luminance.
pub fn temporal_instability(
    test_frames: &[ImageData],
    reference_frames: &[ImageData],
) -> Result<TemporalInstability, MetricsError> {
    let Luminances {
        test: test_lum,
        reference:
            ReferenceLuminance {
                frames: ref_lum,
                mean: ref_mean,
            },
    } = luminances(test_frames, reference_frames)?;
    let pixels = reference_frames[0].pixels.len() as f64;
    let per_pair: Vec<f64> = test_lum
        .par_windows(2)
        .zip(ref_lum.par_windows(2))
        .map(|(t, r)| {
            let sum = ordered_sum(t[0].len(), |i| {
                ((t[1][i] - t[0][i]) - (r[1][i] - r[0][i])).abs()
            });
            sum / pixels / ref_mean
        })
        .collect();
    let mean = per_pair.iter().sum::<f64>() / per_pair.len() as f64;
    Ok(TemporalInstability { per_pair, mean })
}

/// Per frame, the luminance of every pixel, of a test and a reference sequence.
pub(super) struct Luminances {
    /// The test sequence's, per frame and pixel.
    pub test: Vec<Vec<f64>>,
    /// The reference's ([`ReferenceLuminance`]).
    pub reference: ReferenceLuminance,
}

/// Per frame, the luminance of every pixel of a reference sequence, and their mean.
pub(super) struct ReferenceLuminance {
    /// Per frame and pixel.
    pub frames: Vec<Vec<f64>>,
    /// The mean over the whole sequence (positive).
    pub mean: f64,
}

/// The luminances of `test_frames` and `reference_frames`, checking what [`temporal_instability`]
/// requires.
pub(super) fn luminances(
    test_frames: &[ImageData],
    reference_frames: &[ImageData],
) -> Result<Luminances, MetricsError> {
    let reference = reference_luminance(test_frames, reference_frames)?;
    Ok(Luminances {
        test: frame_luminances(test_frames),
        reference,
    })
}

/// The luminances of `reference_frames` and their mean, checking what [`temporal_instability`]
/// requires of them and of `test_frames` (whose luminances are not computed).
pub(super) fn reference_luminance(
    test_frames: &[ImageData],
    reference_frames: &[ImageData],
) -> Result<ReferenceLuminance, MetricsError> {
    if test_frames.len() != reference_frames.len() {
        return Err(MetricsError::FrameCountMismatch {
            test: test_frames.len(),
            reference: reference_frames.len(),
        });
    }
    if test_frames.len() < 2 {
        return Err(MetricsError::TooFewFrames {
            count: test_frames.len(),
        });
    }
    let first = &reference_frames[0];
    for frame in test_frames.iter().chain(reference_frames) {
        check_pair(frame, first)?;
    }
    let frames = frame_luminances(reference_frames);
    let pixels = first.pixels.len() as f64;
    let mean = frames.iter().flatten().sum::<f64>() / (pixels * frames.len() as f64);
    if !(mean.is_finite() && mean > 0.0) {
        return Err(MetricsError::DegenerateReference { mean });
    }
    Ok(ReferenceLuminance { frames, mean })
}

/// Per frame, the luminance of every pixel of `frames`.
fn frame_luminances(frames: &[ImageData]) -> Vec<Vec<f64>> {
    frames
        .par_iter()
        .map(|f| {
            f.pixels
                .par_iter()
                .map(|&p| f64::from(rec709_luminance(p)))
                .collect()
        })
        .collect()
}
