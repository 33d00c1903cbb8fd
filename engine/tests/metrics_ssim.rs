//! SSIM and DSSIM.

use lucid_engine::capture::ImageData;
use lucid_engine::metrics::{dssim, ssim, MetricsError, SsimMode};

const MODES: [SsimMode; 2] = [SsimMode::Luminance, SsimMode::PerChannel];

/// A 40x30 image with smooth structure in every channel.
fn textured() -> ImageData {
    let (w, h) = (40u32, 30u32);
    let pixels = (0..h)
        .flat_map(|y| {
            (0..w).map(move |x| {
                let (fx, fy) = (x as f32 / w as f32, y as f32 / h as f32);
                [fx, 0.5 + 0.4 * (fx * 9.0 + fy * 4.0).sin(), fy * fy, 1.0]
            })
        })
        .collect();
    ImageData::from_pixels(w, h, pixels).unwrap()
}

/// `image` plus deterministic pseudo-random noise of the given amplitude.
fn noisy(image: &ImageData, amplitude: f32) -> ImageData {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut noise = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        ((state >> 40) as f32 / (1u64 << 24) as f32 - 0.5) * 2.0 * amplitude
    };
    let mut out = image.clone();
    for p in &mut out.pixels {
        for v in &mut p[..3] {
            *v = (*v + noise()).clamp(0.0, 1.0);
        }
    }
    out
}

fn constant(w: u32, h: u32, v: f32) -> ImageData {
    ImageData::from_pixels(w, h, vec![[v, v, v, 1.0]; (w * h) as usize]).unwrap()
}

#[test]
fn identical_images_have_ssim_one_and_dssim_zero() {
    let image = textured();
    for mode in MODES {
        let s = ssim(&image, &image, mode).unwrap();
        assert_eq!(s, 1.0, "{mode:?}");
        assert_eq!(dssim(s), 0.0);
    }
}

#[test]
fn constant_images_reduce_to_the_luminance_term() {
    // With no variance the structure term is C2 / C2 = 1, leaving
    // (2ab + C1) / (a^2 + b^2 + C1) with C1 = 1e-4.
    let (a, b) = (0.5f64, 0.25f64);
    let expected = (2.0 * a * b + 1e-4) / (a * a + b * b + 1e-4);
    for mode in MODES {
        let s = ssim(&constant(16, 12, 0.25), &constant(16, 12, 0.5), mode).unwrap();
        assert!((s - expected).abs() < 1e-4, "{mode:?}: {s} vs {expected}");
    }
}

#[test]
fn ssim_falls_as_noise_grows() {
    let reference = textured();
    for mode in MODES {
        let mut previous = 1.0;
        for amplitude in [0.01, 0.05, 0.1, 0.3] {
            let s = ssim(&noisy(&reference, amplitude), &reference, mode).unwrap();
            assert!(
                s < previous,
                "{mode:?}: SSIM {s} at noise {amplitude} not below {previous}"
            );
            assert!(dssim(s) > 0.0);
            previous = s;
        }
        assert!(
            previous < 0.5,
            "{mode:?}: heavy noise should score low, got {previous}"
        );
    }
}

#[test]
fn per_channel_mode_sees_chroma_changes_that_luminance_mode_misses() {
    // Red and blue move in opposite directions by amounts that cancel in
    // Rec.709 luminance: 0.2126 * dr + 0.0722 * db = 0.
    let (w, h) = (24u32, 24u32);
    let reference = constant(w, h, 0.5);
    let pixels = (0..w * h)
        .map(|i| {
            let dr = if (i % w + i / w) % 2 == 0 { 0.1 } else { -0.1 };
            [0.5 + dr, 0.5, 0.5 - dr * 0.2126 / 0.0722, 1.0]
        })
        .collect();
    let test = ImageData::from_pixels(w, h, pixels).unwrap();
    let luminance = ssim(&test, &reference, SsimMode::Luminance).unwrap();
    let per_channel = ssim(&test, &reference, SsimMode::PerChannel).unwrap();
    assert!(luminance > 0.999, "luminance SSIM {luminance}");
    assert!(per_channel < 0.8, "per-channel SSIM {per_channel}");
}

#[test]
fn values_are_clamped_to_the_unit_range() {
    let bright = constant(12, 12, 3.0);
    let white = constant(12, 12, 1.0);
    for mode in MODES {
        assert_eq!(ssim(&bright, &white, mode).unwrap(), 1.0);
    }
}

#[test]
fn dssim_is_one_over_ssim_minus_one() {
    assert_eq!(dssim(1.0), 0.0);
    assert_eq!(dssim(0.5), 1.0);
    assert!((dssim(0.8) - 0.25).abs() < 1e-12);
}

#[test]
fn mismatched_sizes_are_errors() {
    let result = ssim(
        &constant(4, 4, 0.5),
        &constant(4, 5, 0.5),
        SsimMode::Luminance,
    );
    assert!(matches!(result, Err(MetricsError::SizeMismatch { .. })));
}

#[test]
fn images_smaller_than_the_window_are_an_error() {
    for (w, h) in [(10, 40), (40, 10)] {
        let image =
            ImageData::from_pixels(w, h, vec![[0.5, 0.5, 0.5, 1.0]; (w * h) as usize]).unwrap();
        let err = ssim(&image, &image, SsimMode::Luminance).unwrap_err();
        assert!(
            matches!(err, MetricsError::InvalidParameter { .. }),
            "{w}x{h}: {err}"
        );
        assert!(err.to_string().contains("11x11"), "{err}");
    }
    let side = ImageData::from_pixels(11, 11, vec![[0.5, 0.5, 0.5, 1.0]; 121]).unwrap();
    assert_eq!(ssim(&side, &side, SsimMode::Luminance).unwrap(), 1.0);
}
