//! LDR-FLIP: known properties and agreement with the reference
//! implementation.

use lucid_engine::capture::{srgb_decode, srgb_encode, ImageData};
use lucid_engine::metrics::{flip, MetricsError, DEFAULT_PIXELS_PER_DEGREE};

const PPD: f64 = DEFAULT_PIXELS_PER_DEGREE;

fn from_fn(w: u32, h: u32, f: impl Fn(u32, u32) -> [f32; 3]) -> ImageData {
    let pixels = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let [r, g, b] = f(x, y);
            [r, g, b, 1.0]
        })
        .collect();
    ImageData::from_pixels(w, h, pixels).unwrap()
}

fn textured() -> ImageData {
    from_fn(48, 40, |x, y| {
        let (fx, fy) = (x as f32 / 48.0, y as f32 / 40.0);
        [
            fx,
            0.5 + 0.4 * (fx * 11.0).sin() * (fy * 5.0).cos(),
            1.0 - fy,
        ]
    })
}

fn noisy(image: &ImageData, amplitude: f32) -> ImageData {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut out = image.clone();
    for p in &mut out.pixels {
        for v in &mut p[..3] {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let n = ((state >> 40) as f32 / (1u64 << 24) as f32 - 0.5) * 2.0 * amplitude;
            *v = (*v + n).clamp(0.0, 1.0);
        }
    }
    out
}

/// A linear value as it comes back from an 8-bit sRGB PNG.
fn quantized(v: f32) -> f32 {
    srgb_decode((srgb_encode(v) * 255.0).round() / 255.0)
}

#[test]
fn identical_images_score_zero_everywhere() {
    let image = textured();
    let result = flip(&image, &image, PPD).unwrap();
    assert_eq!(result.mean, 0.0);
    assert_eq!((result.width, result.height), (48, 40));
    assert_eq!(result.error_map.len(), 48 * 40);
    assert!(result.error_map.iter().all(|&e| e == 0.0));
}

#[test]
fn black_against_white_is_close_to_one() {
    // Flat images have no features, so FLIP is the colour error alone:
    // HyAB(white, black) = 100, 100^0.7 = 25.1 lies above 0.4 * cmax = 16.5
    // (cmax = HyAB(green, blue)^0.7 = 41.3), giving 0.95 + 0.05 * 0.35.
    let black = from_fn(32, 32, |_, _| [0.0; 3]);
    let white = from_fn(32, 32, |_, _| [1.0; 3]);
    let result = flip(&black, &white, PPD).unwrap();
    assert!((result.mean - 0.9674).abs() < 1e-3, "{}", result.mean);
    assert!(result.error_map.iter().all(|&e| (e - 0.9674).abs() < 1e-3));
}

#[test]
fn error_grows_with_noise() {
    let reference = textured();
    let mut previous = 0.0;
    for amplitude in [0.01, 0.03, 0.1, 0.3] {
        let mean = flip(&noisy(&reference, amplitude), &reference, PPD)
            .unwrap()
            .mean;
        assert!(
            mean > previous,
            "FLIP {mean} at noise {amplitude} not above {previous}"
        );
        previous = mean;
    }
}

#[test]
fn error_is_symmetric_and_in_unit_range() {
    let a = textured();
    let b = noisy(&a, 0.2);
    let ab = flip(&a, &b, PPD).unwrap();
    let ba = flip(&b, &a, PPD).unwrap();
    assert!((ab.mean - ba.mean).abs() < 1e-6);
    assert!(ab.error_map.iter().all(|e| (0.0..=1.0).contains(e)));
}

#[test]
fn fine_noise_matters_less_to_a_distant_observer() {
    let reference = textured();
    let test = noisy(&reference, 0.1);
    let near = flip(&test, &reference, 20.0).unwrap().mean;
    let far = flip(&test, &reference, 150.0).unwrap().mean;
    assert!(far < near, "far {far} should be below near {near}");
}

/// Means computed with NVIDIA's reference implementation (the
/// `flip-evaluator` 1.7 Python package, LDR mode, default 67.02 ppd) on the
/// same images stored as 8-bit sRGB PNGs.
#[test]
fn matches_the_reference_implementation() {
    let (w, h) = (67, 45);
    let red = [0.8, 0.2, 0.1].map(quantized);
    let blue = [0.1, 0.3, 0.9].map(quantized);
    let checker = |shift: u32| {
        from_fn(w, h, move |x, y| {
            if ((x + shift) / 8 + y / 8) % 2 == 0 {
                red
            } else {
                blue
            }
        })
    };
    let shifted = flip(&checker(3), &checker(0), PPD).unwrap().mean;
    assert!((shifted - 0.265_952).abs() < 1e-4, "{shifted}");

    let grey = from_fn(w, h, |_, _| [quantized(0.2); 3]);
    let dotted = from_fn(w, h, |x, y| {
        if (x, y) == (30, 20) {
            [1.0; 3]
        } else {
            [quantized(0.18); 3]
        }
    });
    let dot = flip(&dotted, &grey, PPD).unwrap().mean;
    assert!((dot - 0.107_395).abs() < 1e-4, "{dot}");
}

#[test]
fn bad_arguments_are_errors() {
    let a = textured();
    let small = from_fn(4, 4, |_, _| [0.5; 3]);
    assert!(matches!(
        flip(&a, &small, PPD),
        Err(MetricsError::SizeMismatch { .. })
    ));
    for ppd in [0.0, -3.0, f64::NAN, f64::INFINITY, 1.0e6] {
        assert!(matches!(
            flip(&a, &a, ppd),
            Err(MetricsError::InvalidParameter {
                name: "pixels_per_degree",
                ..
            })
        ));
    }
}
