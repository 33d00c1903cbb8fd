//! Display encoding: exposure, tone curves and the sRGB transfer functions.

use lucid_engine::capture::{srgb_decode, srgb_encode, ImageData, PngEncoding, ToneCurve};

#[test]
fn srgb_transfer_functions_invert_each_other() {
    assert_eq!(srgb_encode(0.0), 0.0);
    assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
    assert!((srgb_encode(0.18) - 0.461_356).abs() < 1e-4);
    for i in 0..=100 {
        let v = i as f32 / 100.0;
        assert!((srgb_decode(srgb_encode(v)) - v).abs() < 1e-5, "{v}");
    }
    assert_eq!(srgb_encode(f32::NAN), 0.0);
    assert_eq!(srgb_encode(5.0), srgb_encode(1.0));
}

#[test]
fn clamp_curve_only_clamps() {
    assert_eq!(ToneCurve::Clamp.apply([0.25, 2.0, -1.0]), [0.25, 1.0, 0.0]);
}

#[test]
fn aces_curve_matches_the_narkowicz_fit_and_saturates() {
    let x = 0.5f32;
    let expected = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    let [r, _, _] = ToneCurve::Aces.apply([x, 0.0, 0.0]);
    assert!((r - expected).abs() < 1e-6);
    assert_eq!(ToneCurve::Aces.apply([0.0; 3]), [0.0; 3]);
    assert_eq!(ToneCurve::Aces.apply([f32::INFINITY; 3]), [1.0; 3]);
}

#[test]
fn agx_curve_is_monotone_and_bounded() {
    let mut previous = -1.0f32;
    for i in 0..200 {
        let v = 2f32.powf(i as f32 / 10.0 - 12.0);
        let [r, g, b] = ToneCurve::AgX.apply([v, v, v]);
        assert!((0.0..=1.0).contains(&r) && (0.0..=1.0).contains(&g) && (0.0..=1.0).contains(&b));
        assert!(g >= previous, "AgX not monotone at {v}: {g} < {previous}");
        previous = g;
    }
    assert!(ToneCurve::AgX.apply([0.0; 3])[1] < 0.01);
    assert!(ToneCurve::AgX.apply([1.0e4; 3])[1] > 0.9);
}

#[test]
fn exposure_is_in_stops() {
    let brighter = PngEncoding {
        exposure: 2.0,
        tone: ToneCurve::Clamp,
    };
    assert_eq!(
        brighter.tone_map_pixel([0.125, 0.0625, 0.75, 0.5]),
        [0.5, 0.25, 1.0, 1.0]
    );
    let darker = PngEncoding {
        exposure: -1.0,
        tone: ToneCurve::Clamp,
    };
    assert_eq!(
        darker.tone_map_pixel([0.5, 0.25, 2.0, 0.0]),
        [0.25, 0.125, 1.0, 1.0]
    );
    let encoded = darker.encode_pixel([0.5, 0.0, 0.0, 0.5]);
    assert!((encoded[0] - srgb_encode(0.25)).abs() < 1e-6);
}

#[test]
fn whole_image_conversions_match_the_per_pixel_ones() {
    let image =
        ImageData::from_pixels(2, 1, vec![[0.1, 4.0, 0.5, 0.3], [0.0, 0.02, 9.0, 1.0]]).unwrap();
    let encoding = PngEncoding {
        exposure: -0.5,
        tone: ToneCurve::AgX,
    };
    let display = encoding.to_display(&image);
    let linear = encoding.tone_map(&image);
    for i in 0..2 {
        assert_eq!(display.pixels[i], encoding.encode_pixel(image.pixels[i]));
        assert_eq!(linear.pixels[i], encoding.tone_map_pixel(image.pixels[i]));
    }
}
