//! Every metric of a rendered sequence against its reference sequence, per frame and summarised.

use super::{dssim, flip, rel_mse, ssim, temporal_instability, MetricsError, SsimMode};
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
    let s = ssim(
        &display.to_display(test),
        &display.to_display(reference),
        SsimMode::Luminance,
    )?;
    Ok(FrameMetrics {
        rel_mse: rel_mse(test, reference, DEFAULT_REL_MSE_EPSILON)?,
        ssim: s,
        dssim: dssim(s),
        flip: flip(
            &display.tone_map(test),
            &display.tone_map(reference),
            DEFAULT_PIXELS_PER_DEGREE,
        )?
        .mean,
        temporal_instability: 0.0,
    })
}

/// Compares `test` with `reference` frame by frame; `display` maps linear frames to the display
/// for SSIM and FLIP. Needs at least two frames of equal sizes and a reference that is not black.
pub fn evaluate_sequence(
    test: &[ImageData],
    reference: &[ImageData],
    display: &PngEncoding,
) -> Result<SequenceMetrics, MetricsError> {
    let instability = temporal_instability(test, reference)?;
    let frames = test
        .iter()
        .zip(reference)
        .enumerate()
        .map(|(i, (t, r))| {
            Ok(FrameMetrics {
                temporal_instability: i
                    .checked_sub(1)
                    .map_or(0.0, |pair| instability.per_pair[pair]),
                ..evaluate_frame(t, r, display)?
            })
        })
        .collect::<Result<Vec<_>, MetricsError>>()?;
    let n = frames.len() as f64;
    let mean_of = |f: fn(&FrameMetrics) -> f64| frames.iter().map(f).sum::<f64>() / n;
    let mean = FrameMetrics {
        rel_mse: mean_of(|f| f.rel_mse),
        ssim: mean_of(|f| f.ssim),
        dssim: mean_of(|f| f.dssim),
        flip: mean_of(|f| f.flip),
        temporal_instability: instability.mean,
    };
    Ok(SequenceMetrics { frames, mean })
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
