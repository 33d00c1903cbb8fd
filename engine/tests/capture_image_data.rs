//! `ImageData` construction and accessors.

use lucid_engine::capture::{rec709_luminance, CaptureError, ImageData};

#[test]
fn new_is_opaque_black_of_the_right_size() {
    let image = ImageData::new(3, 2);
    assert_eq!(image.pixel_count(), 6);
    assert!(image.pixels.iter().all(|&p| p == [0.0, 0.0, 0.0, 1.0]));
}

#[test]
fn from_pixels_checks_the_length() {
    let error = ImageData::from_pixels(3, 2, vec![[0.0; 4]; 5]).unwrap_err();
    assert!(matches!(
        error,
        CaptureError::PixelCountMismatch {
            expected: 6,
            actual: 5,
            ..
        }
    ));
    assert!(ImageData::from_pixels(3, 2, vec![[0.0; 4]; 6]).is_ok());
    assert!(ImageData::from_pixels(0, 0, Vec::new()).is_ok());
}

#[test]
fn get_is_row_major_and_bounds_checked() {
    let pixels = (0..6).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect();
    let image = ImageData::from_pixels(3, 2, pixels).unwrap();
    assert_eq!(image.get(0, 0).unwrap()[0], 0.0);
    assert_eq!(image.get(2, 0).unwrap()[0], 2.0);
    assert_eq!(image.get(1, 1).unwrap()[0], 4.0);
    assert_eq!(image.get(3, 0), None);
    assert_eq!(image.get(0, 2), None);
    assert_eq!(image.luminance(5, 5), None);
}

#[test]
fn luminance_uses_rec709_weights() {
    let image = ImageData::from_pixels(
        3,
        1,
        vec![
            [1.0, 0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 1.0],
        ],
    )
    .unwrap();
    assert_eq!(image.luminance(0, 0), Some(0.2126));
    assert_eq!(image.luminance(1, 0), Some(0.7152));
    assert_eq!(image.luminance(2, 0), Some(0.0722));
    assert!((rec709_luminance([1.0, 1.0, 1.0, 0.0]) - 1.0).abs() < 1e-6);
}

#[test]
fn mean_rgb_averages_each_channel() {
    let image =
        ImageData::from_pixels(2, 1, vec![[1.0, 2.0, 3.0, 0.0], [3.0, 6.0, -3.0, 1.0]]).unwrap();
    assert_eq!(image.mean_rgb(), [2.0, 4.0, 0.0]);
    assert_eq!(ImageData::new(0, 0).mean_rgb(), [0.0; 3]);
}

#[test]
fn has_non_finite_detects_nan_and_infinity_in_any_channel() {
    let mut image = ImageData::new(2, 2);
    assert!(!image.has_non_finite());
    image.pixels[3][3] = f32::NAN;
    assert!(image.has_non_finite());
    image.pixels[3][3] = 1.0;
    image.pixels[1][0] = f32::NEG_INFINITY;
    assert!(image.has_non_finite());
}
