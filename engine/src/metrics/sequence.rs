//! Every metric of a rendered sequence against its reference sequence, per frame and summarised.

use rayon::prelude::*;

use super::check::check_pair;
use super::{dssim, rel_mse, temporal_instability, MetricsError, SsimMode};
use super::{FlipReference, SsimReference};
use super::{DEFAULT_PIXELS_PER_DEGREE, DEFAULT_REL_MSE_EPSILON};
use crate::capture::{ImageData, PngEncoding};

/// The metrics of one frame against its reference frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameMetrics {
    /// Relative MSE of the linear images.
    pub rel_mse: f64,
    /// Luminance SSIM of the display-encoded images.
    pub ssim: f64,
    /// `1 / ssim - 1`.
    pub dssim: f64,
    /// Mean LDR-FLIP of the tone-mapped images.
    pub flip: f64,
    /// Temporal instability of the step from the previous frame (0 for the first frame).
    pub temporal_instability: f64,
}

/// The metrics of a sequence: per frame and their means.
#[derive(Clone, Debug, PartialEq)]
pub struct SequenceMetrics {
    /// One entry per frame.
    pub frames: Vec<FrameMetrics>,
    /// Means over the frames (temporal instability: over the frame pairs).
    pub mean: FrameMetrics,
}

/// Compares one frame with its reference as [`evaluate_sequence`] compares each frame: relative MSE
/// of the linear images, SSIM (and DSSIM) of the display-encoded images, FLIP of the tone-mapped
/// images, `display` mapping linear to display. Temporal instability is 0: one frame has no step.
pub fn evaluate_frame(
    test: &ImageData,
    reference: &ImageData,
    display: &PngEncoding,
) -> Result<FrameMetrics, MetricsError> {
    check_pair(test, reference)?;
    PreparedReference::new(reference, display)?.evaluate(test)
}

/// A reference frame prepared once (its display images, SSIM's windowed statistics, FLIP's
/// filtered colours and feature responses) for comparing many test frames with it as
/// [`evaluate_frame`] does: each comparison then computes the test side only.
pub struct PreparedReference {
    linear: ImageData,
    display: PngEncoding,
    ssim: SsimReference,
    flip: FlipReference,
}

impl PreparedReference {
    /// Prepares `reference`, `display` mapping linear to display.
    pub fn new(reference: &ImageData, display: &PngEncoding) -> Result<Self, MetricsError> {
        let (ssim, flip) = rayon::join(
            || SsimReference::new(&display.to_display(reference), SsimMode::Luminance),
            || FlipReference::new(&display.tone_map(reference), DEFAULT_PIXELS_PER_DEGREE),
        );
        Ok(Self {
            linear: reference.clone(),
            display: *display,
            ssim: ssim?,
            flip: flip?,
        })
    }

    /// The metrics of `test` against the reference, as [`evaluate_frame`] computes them.
    pub fn evaluate(&self, test: &ImageData) -> Result<FrameMetrics, MetricsError> {
        let (s, (flip, rel_mse)) = rayon::join(
            || self.ssim.compare(&self.display.to_display(test)),
            || {
                rayon::join(
                    || self.flip.compare(&self.display.tone_map(test)),
                    || rel_mse(test, &self.linear, DEFAULT_REL_MSE_EPSILON),
                )
            },
        );
        let s = s?;
        Ok(FrameMetrics {
            rel_mse: rel_mse?,
            ssim: s,
            dssim: dssim(s),
            flip: flip?.mean,
            temporal_instability: 0.0,
        })
    }
}

/// Compares `test` with `reference` frame by frame; `display` maps linear frames to the display
/// for SSIM and FLIP. Needs at least two frames of equal sizes and a reference that is not black.
pub fn evaluate_sequence(
    test: &[ImageData],
    reference: &[ImageData],
    display: &PngEncoding,
) -> Result<SequenceMetrics, MetricsError> {
    let mut all = evaluate_sequences(&[test], reference, display)?;
    Ok(all.remove(0))
}

/// [`evaluate_sequence`] of each of `tests` against the same `reference`, frames in parallel,
/// each reference frame prepared once for all the tests.
pub fn evaluate_sequences(
    tests: &[&[ImageData]],
    reference: &[ImageData],
    display: &PngEncoding,
) -> Result<Vec<SequenceMetrics>, MetricsError> {
    let instabilities = tests
        .iter()
        .map(|test| temporal_instability(test, reference))
        .collect::<Result<Vec<_>, _>>()?;
    let per_frame: Vec<Vec<FrameMetrics>> = reference
        .par_iter()
        .enumerate()
        .map(|(i, r)| {
            let prepared = PreparedReference::new(r, display)?;
            tests
                .iter()
                .map(|test| {
                    check_pair(&test[i], r)?;
                    prepared.evaluate(&test[i])
                })
                .collect()
        })
        .collect::<Result<_, MetricsError>>()?;
    Ok(instabilities
        .into_iter()
        .enumerate()
        .map(|(t, instability)| {
            let frames: Vec<FrameMetrics> = per_frame
                .iter()
                .enumerate()
                .map(|(i, metrics)| FrameMetrics {
                    temporal_instability: i
                        .checked_sub(1)
                        .map_or(0.0, |pair| instability.per_pair[pair]),
                    ..metrics[t]
                })
                .collect();
            let n = frames.len() as f64;
            let mean_of = |f: fn(&FrameMetrics) -> f64| frames.iter().map(f).sum::<f64>() / n;
            let mean = FrameMetrics {
                rel_mse: mean_of(|f| f.rel_mse),
                ssim: mean_of(|f| f.ssim),
                dssim: mean_of(|f| f.dssim),
                flip: mean_of(|f| f.flip),
                temporal_instability: instability.mean,
            };
            SequenceMetrics { frames, mean }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(value: f32) -> ImageData {
        ImageData::from_pixels(16, 16, vec![[value, value, value, 1.0]; 256]).unwrap()
    }

    #[test]
    fn identical_sequences_are_perfect() {
        let frames = [frame(0.5), frame(0.6), frame(0.4)];
        let m = evaluate_sequence(&frames, &frames, &PngEncoding::default()).unwrap();
        assert_eq!(m.frames.len(), 3);
        assert_eq!(m.mean.rel_mse, 0.0);
        assert_eq!(m.mean.ssim, 1.0);
        assert_eq!(m.mean.dssim, 0.0);
        assert_eq!(m.mean.flip, 0.0);
        assert_eq!(m.mean.temporal_instability, 0.0);
    }

    #[test]
    fn a_flickering_sequence_is_unstable() {
        let reference = [frame(0.5), frame(0.5), frame(0.5)];
        let test = [frame(0.4), frame(0.6), frame(0.4)];
        let m = evaluate_sequence(&test, &reference, &PngEncoding::default()).unwrap();
        assert_eq!(m.frames[0].temporal_instability, 0.0);
        assert!((m.frames[1].temporal_instability - 0.4).abs() < 1e-6);
        assert!(m.mean.rel_mse > 0.0 && m.mean.flip > 0.0);
    }

    #[test]
    fn a_frame_alone_is_evaluated_as_in_its_sequence() {
        let reference = [frame(0.5), frame(0.5)];
        let test = [frame(0.4), frame(0.6)];
        let m = evaluate_sequence(&test, &reference, &PngEncoding::default()).unwrap();
        let alone = evaluate_frame(&test[1], &reference[1], &PngEncoding::default()).unwrap();
        assert_eq!(
            alone,
            FrameMetrics {
                temporal_instability: 0.0,
                ..m.frames[1]
            }
        );
    }

    #[test]
    fn one_frame_is_an_error() {
        let one = [frame(0.5)];
        assert!(evaluate_sequence(&one, &one, &PngEncoding::default()).is_err());
    }
}
