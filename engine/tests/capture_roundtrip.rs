//! Save/load round trips through EXR and PNG.

use std::path::PathBuf;

use lucid_engine::capture::{
    load, load_exr, load_png, save, save_exr, save_png, srgb_encode, ExrPrecision, ImageData,
    PngEncoding,
};

fn temp_path(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("capture_roundtrip");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A 7x5 image with distinct, awkward values in every channel: negatives,
/// large HDR values, tiny values and non-trivial alpha.
fn hdr_image() -> ImageData {
    let (w, h) = (7u32, 5u32);
    let pixels = (0..w * h)
        .map(|i| {
            let t = i as f32;
            [
                t * 0.137 - 1.5,
                (t * 1.618).sin() * 1000.0,
                1.0e-3 / (t + 1.0),
                (t / 34.0).clamp(0.0, 1.0),
            ]
        })
        .collect();
    ImageData::from_pixels(w, h, pixels).unwrap()
}

/// A 16x9 image with values in [0, 1] (alpha 1), as a PNG can represent.
fn ldr_image() -> ImageData {
    let (w, h) = (16u32, 9u32);
    let pixels = (0..w * h)
        .map(|i| {
            let t = i as f32 / (w * h) as f32;
            [t, 1.0 - t, (t * 7.0).fract(), 1.0]
        })
        .collect();
    ImageData::from_pixels(w, h, pixels).unwrap()
}

#[test]
fn exr_f32_round_trip_is_exact() {
    let image = hdr_image();
    let path = temp_path("f32.exr");
    save_exr(&path, &image, ExrPrecision::F32).unwrap();
    assert_eq!(load_exr(&path).unwrap(), image);
}

#[test]
fn exr_f16_round_trip_is_within_half_precision() {
    let image = hdr_image();
    let path = temp_path("f16.exr");
    save_exr(&path, &image, ExrPrecision::F16).unwrap();
    let loaded = load_exr(&path).unwrap();
    assert_eq!((loaded.width, loaded.height), (image.width, image.height));
    let mut any_rounded = false;
    for (a, b) in image
        .pixels
        .iter()
        .flatten()
        .zip(loaded.pixels.iter().flatten())
    {
        // Half floats keep 11 significant bits: relative error <= 2^-11 for
        // normal numbers, absolute error <= 2^-25 in the subnormal range.
        let tolerance = (a.abs() * 2f32.powi(-11)).max(2f32.powi(-25));
        assert!((a - b).abs() <= tolerance, "{a} became {b}");
        any_rounded |= a != b;
    }
    assert!(
        any_rounded,
        "f16 output should differ from f32 input somewhere"
    );
}

#[test]
fn png_round_trip_is_within_one_step_after_srgb() {
    let image = ldr_image();
    let path = temp_path("ldr.png");
    save_png(&path, &image, &PngEncoding::default()).unwrap();
    let loaded = load_png(&path).unwrap();
    assert_eq!((loaded.width, loaded.height), (image.width, image.height));
    for (a, b) in image.pixels.iter().zip(&loaded.pixels) {
        for c in 0..3 {
            let step = (srgb_encode(a[c]) - srgb_encode(b[c])).abs() * 255.0;
            assert!(
                step <= 1.0,
                "channel {c}: {} became {} ({step} steps)",
                a[c],
                b[c]
            );
        }
        assert_eq!(b[3], 1.0);
    }
}

#[test]
fn png_stores_opaque_alpha_and_clamps_out_of_range() {
    let image = ImageData::from_pixels(
        2,
        1,
        vec![[2.0, -1.0, 0.5, 0.25], [f32::NAN, 0.0, 0.0, 0.0]],
    )
    .unwrap();
    let path = temp_path("clamped.png");
    save_png(&path, &image, &PngEncoding::default()).unwrap();
    let loaded = load_png(&path).unwrap();
    assert_eq!(loaded.pixels[0][0], 1.0);
    assert_eq!(loaded.pixels[0][1], 0.0);
    assert_eq!(loaded.pixels[1], [0.0, 0.0, 0.0, 1.0]);
    assert!(loaded.pixels.iter().all(|p| p[3] == 1.0));
}

#[test]
fn save_and_load_pick_the_format_by_extension() {
    let hdr = hdr_image();
    let exr_path = temp_path("by_extension.EXR");
    save(&exr_path, &hdr).unwrap();
    assert_eq!(
        load(&exr_path).unwrap(),
        hdr,
        ".exr must be saved as lossless f32"
    );
    assert_eq!(
        &std::fs::read(&exr_path).unwrap()[..4],
        &[0x76, 0x2f, 0x31, 0x01]
    );

    let ldr = ldr_image();
    let png_path = temp_path("by_extension.png");
    save(&png_path, &ldr).unwrap();
    assert_eq!(&std::fs::read(&png_path).unwrap()[1..4], b"PNG");
    assert_eq!(load(&png_path).unwrap(), load_png(&png_path).unwrap());
}

#[test]
fn exr_with_rgb_only_loads_with_opaque_alpha() {
    use exr::prelude::{SpecificChannels, Vec2, WritableImage};
    let path = temp_path("rgb_only.exr");
    let channels =
        SpecificChannels::rgb(|pos: Vec2<usize>| (pos.x() as f32, pos.y() as f32, 0.5f32));
    exr::prelude::Image::from_channels((3, 2), channels)
        .write()
        .to_file(&path)
        .unwrap();
    let loaded = load_exr(&path).unwrap();
    assert_eq!((loaded.width, loaded.height), (3, 2));
    assert_eq!(loaded.get(2, 1), Some([2.0, 1.0, 0.5, 1.0]));
    assert!(loaded.pixels.iter().all(|p| p[3] == 1.0));
}
