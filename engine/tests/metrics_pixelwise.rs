//! MSE, relative MSE, PSNR, maximum error and channel means on small
//! synthetic images with hand-computed results.

use lucid_engine::capture::ImageData;
use lucid_engine::metrics::{
    max_abs_error, mean_per_channel, mse, psnr, rel_mse, MetricsError, DEFAULT_REL_MSE_EPSILON,
};

fn image(pixels: Vec<[f32; 4]>) -> ImageData {
    ImageData::from_pixels(pixels.len() as u32, 1, pixels).unwrap()
}

/// test = [(1, 2, 3), (0.1, 0, 0)], reference = [(1, 0.5, 2), (0, 0, 1)].
fn pair() -> (ImageData, ImageData) {
    (
        image(vec![[1.0, 2.0, 3.0, 0.5], [0.1, 0.0, 0.0, 1.0]]),
        image(vec![[1.0, 0.5, 2.0, 1.0], [0.0, 0.0, 1.0, 1.0]]),
    )
}

fn assert_close(actual: f64, expected: f64, tolerance: f64) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{actual} != {expected}"
    );
}

#[test]
fn mse_matches_hand_computation() {
    let (test, reference) = pair();
    // Squared differences: 0, 2.25, 1, 0.01, 0, 1 -> 4.26 / 6.
    assert_close(mse(&test, &reference).unwrap(), 4.26 / 6.0, 1e-7);
    assert_eq!(mse(&reference, &reference).unwrap(), 0.0);
}

#[test]
fn rel_mse_matches_hand_computation() {
    let (test, reference) = pair();
    // (t - r)^2 / (r^2 + 0.01): 0, 2.25/0.26, 1/4.01, 0.01/0.01, 0, 1/1.01.
    let expected = (2.25 / 0.26 + 1.0 / 4.01 + 1.0 + 1.0 / 1.01) / 6.0;
    assert_close(
        rel_mse(&test, &reference, DEFAULT_REL_MSE_EPSILON).unwrap(),
        expected,
        1e-6,
    );
    // A larger eps damps the near-black reference pixel.
    let damped = (2.25 / 1.25 + 1.0 / 5.0 + 0.01 / 1.0 + 1.0 / 2.0) / 6.0;
    assert_close(rel_mse(&test, &reference, 1.0).unwrap(), damped, 1e-7);
}

#[test]
fn rel_mse_rejects_non_positive_eps() {
    let (test, reference) = pair();
    for eps in [0.0, -1.0, f64::NAN] {
        assert!(matches!(
            rel_mse(&test, &reference, eps),
            Err(MetricsError::InvalidParameter { name: "eps", .. })
        ));
    }
}

#[test]
fn psnr_matches_hand_computation() {
    let reference = image(vec![[0.5; 4]; 4]);
    let test = image(vec![[0.6, 0.4, 0.6, 0.0]; 4]);
    // MSE = 0.01 -> 10 log10(1 / 0.01) = 20 dB; with peak 2, 10 log10(400).
    assert_close(psnr(&test, &reference, 1.0).unwrap(), 20.0, 1e-5);
    assert_close(
        psnr(&test, &reference, 2.0).unwrap(),
        10.0 * 400f64.log10(),
        1e-5,
    );
    assert_eq!(psnr(&reference, &reference, 1.0).unwrap(), f64::INFINITY);
    assert!(psnr(&test, &reference, 0.0).is_err());
}

#[test]
fn max_abs_error_finds_the_largest_rgb_difference() {
    let (test, reference) = pair();
    assert_eq!(max_abs_error(&test, &reference).unwrap(), 1.5);
    let mut with_nan = test.clone();
    with_nan.pixels[0][1] = f32::NAN;
    assert!(max_abs_error(&with_nan, &reference).unwrap().is_nan());
}

#[test]
fn alpha_is_ignored_by_error_metrics() {
    let (_, reference) = pair();
    let mut other_alpha = reference.clone();
    other_alpha.pixels[0][3] = 0.0;
    assert_eq!(mse(&other_alpha, &reference).unwrap(), 0.0);
    assert_eq!(max_abs_error(&other_alpha, &reference).unwrap(), 0.0);
}

#[test]
fn mean_per_channel_includes_alpha() {
    let (test, _) = pair();
    let mean = mean_per_channel(&test).unwrap();
    let expected = [1.1 / 2.0, 1.0, 1.5, 0.75];
    for c in 0..4 {
        assert_close(mean[c], expected[c], 1e-7);
    }
}

#[test]
fn mismatched_empty_and_malformed_images_are_errors() {
    let (test, reference) = pair();
    let wide = ImageData::new(3, 1);
    assert!(matches!(
        mse(&test, &wide),
        Err(MetricsError::SizeMismatch {
            test_width: 2,
            reference_width: 3,
            ..
        })
    ));
    let empty = ImageData::new(0, 0);
    assert!(matches!(
        mse(&empty, &empty),
        Err(MetricsError::EmptyImage { .. })
    ));
    assert!(matches!(
        mean_per_channel(&empty),
        Err(MetricsError::EmptyImage { .. })
    ));
    let mut malformed = reference.clone();
    malformed.pixels.pop();
    assert!(matches!(
        rel_mse(&test, &malformed, 0.01),
        Err(MetricsError::MalformedImage { actual: 1, .. })
    ));
    assert!(matches!(
        max_abs_error(&malformed, &test),
        Err(MetricsError::MalformedImage { .. })
    ));
}
