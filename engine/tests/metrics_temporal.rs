//! Temporal instability of frame sequences.

use lucid_engine::capture::ImageData;
use lucid_engine::metrics::{temporal_instability, MetricsError};

fn grey(v: f32) -> ImageData {
    ImageData::from_pixels(8, 6, vec![[v, v, v, 1.0]; 48]).unwrap()
}

/// A sequence whose frames move a bright bar one pixel per frame.
fn moving_bar(frames: u32) -> Vec<ImageData> {
    (0..frames)
        .map(|t| {
            let pixels = (0..48u32)
                .map(|i| {
                    if i % 8 == t % 8 {
                        [0.9, 0.8, 0.7, 1.0]
                    } else {
                        [0.1, 0.1, 0.1, 1.0]
                    }
                })
                .collect();
            ImageData::from_pixels(8, 6, pixels).unwrap()
        })
        .collect()
}

#[test]
fn identical_sequences_are_perfectly_stable() {
    let frames = moving_bar(5);
    let result = temporal_instability(&frames, &frames).unwrap();
    assert_eq!(result.per_pair, vec![0.0; 4]);
    assert_eq!(result.mean, 0.0);
}

#[test]
fn a_constant_bias_does_not_count_as_instability() {
    let reference = moving_bar(4);
    let biased: Vec<ImageData> = reference
        .iter()
        .map(|f| {
            let mut f = f.clone();
            for p in &mut f.pixels {
                p[1] += 0.25;
            }
            f
        })
        .collect();
    let result = temporal_instability(&biased, &reference).unwrap();
    assert!(result.mean < 1e-6, "{}", result.mean);
}

#[test]
fn flicker_over_a_static_reference_is_measured_relative_to_its_brightness() {
    let reference = vec![grey(0.5); 4];
    let flicker = vec![grey(0.5), grey(0.6), grey(0.5), grey(0.6)];
    let result = temporal_instability(&flicker, &reference).unwrap();
    // Each pair changes luminance by 0.1 where the reference is still; the
    // reference's mean luminance is 0.5, so every pair scores 0.2.
    assert_eq!(result.per_pair.len(), 3);
    for value in &result.per_pair {
        assert!((value - 0.2).abs() < 1e-5, "{value}");
    }
    assert!((result.mean - 0.2).abs() < 1e-5);
}

#[test]
fn per_pair_values_localise_a_single_pop() {
    let reference = vec![grey(0.4); 4];
    let test = vec![grey(0.4), grey(0.4), grey(0.8), grey(0.8)];
    let result = temporal_instability(&test, &reference).unwrap();
    assert!(result.per_pair[0].abs() < 1e-6);
    assert!((result.per_pair[1] - 1.0).abs() < 1e-5);
    assert!(result.per_pair[2].abs() < 1e-6);
    assert!((result.mean - 1.0 / 3.0).abs() < 1e-5);
}

#[test]
fn invalid_sequences_are_errors() {
    let frames = vec![grey(0.5); 3];
    assert!(matches!(
        temporal_instability(&frames[..2], &frames),
        Err(MetricsError::FrameCountMismatch {
            test: 2,
            reference: 3
        })
    ));
    assert!(matches!(
        temporal_instability(&frames[..1], &frames[..1]),
        Err(MetricsError::TooFewFrames { count: 1 })
    ));
    let mixed = vec![grey(0.5), ImageData::new(3, 3), grey(0.5)];
    assert!(matches!(
        temporal_instability(&mixed, &frames),
        Err(MetricsError::SizeMismatch { .. })
    ));
    let black = vec![grey(0.0); 3];
    assert!(matches!(
        temporal_instability(&frames, &black),
        Err(MetricsError::DegenerateReference { .. })
    ));
}
