//! Bad input to the capture module yields errors that name the file.

use std::path::{Path, PathBuf};

use lucid_engine::capture::{
    load, load_exr, load_png, save, save_exr, CaptureError, ExrPrecision, ImageData,
};

fn temp_path(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("capture_errors");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn assert_names(error: &CaptureError, path: &Path) {
    let message = error.to_string();
    assert!(
        message.contains(&path.display().to_string()),
        "error does not name {}: {message}",
        path.display()
    );
}

#[test]
fn missing_files_are_io_errors_naming_the_path() {
    for name in ["missing.exr", "missing.png"] {
        let path = temp_path(name);
        let error = load(&path).unwrap_err();
        assert!(matches!(error, CaptureError::Io { .. }), "{error:?}");
        assert_names(&error, &path);
    }
}

#[test]
fn garbage_bytes_are_decode_errors_naming_the_path() {
    let garbage: Vec<u8> = (0..997u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
        .collect();
    let exr_path = temp_path("garbage.exr");
    let png_path = temp_path("garbage.png");
    std::fs::write(&exr_path, &garbage).unwrap();
    std::fs::write(&png_path, &garbage).unwrap();
    for (path, error) in [
        (&exr_path, load_exr(&exr_path).unwrap_err()),
        (&png_path, load_png(&png_path).unwrap_err()),
    ] {
        assert!(matches!(error, CaptureError::Decode { .. }), "{error:?}");
        assert_names(&error, path);
    }
}

#[test]
fn truncated_and_empty_files_are_errors() {
    let image = ImageData::new(32, 32);
    let good = temp_path("good.exr");
    save_exr(&good, &image, ExrPrecision::F32).unwrap();
    let bytes = std::fs::read(&good).unwrap();
    for (name, length) in [
        ("truncated.exr", bytes.len() / 2),
        ("header_only.exr", 20),
        ("empty.exr", 0),
    ] {
        let path = temp_path(name);
        std::fs::write(&path, &bytes[..length]).unwrap();
        let error = load_exr(&path).unwrap_err();
        assert_names(&error, &path);
    }
    let empty_png = temp_path("empty.png");
    std::fs::write(&empty_png, []).unwrap();
    assert_names(&load_png(&empty_png).unwrap_err(), &empty_png);
}

#[test]
fn exr_without_colour_channels_is_an_unsupported_layout() {
    use exr::prelude::{AnyChannel, AnyChannels, FlatSamples, Image, WritableImage};
    let path = temp_path("depth_only.exr");
    let depth = AnyChannel::new("Z", FlatSamples::F32(vec![1.0; 4 * 3]));
    Image::from_channels((4, 3), AnyChannels::sort(vec![depth].into()))
        .write()
        .to_file(&path)
        .unwrap();
    let error = load_exr(&path).unwrap_err();
    assert!(
        matches!(error, CaptureError::UnsupportedLayout { .. }),
        "{error:?}"
    );
    assert_names(&error, &path);
    assert!(
        error.to_string().contains('Z'),
        "should list the channels found: {error}"
    );
}

#[test]
fn unknown_extensions_are_rejected_naming_the_path() {
    let image = ImageData::new(1, 1);
    for name in ["frame.jpg", "frame", "frame.exr.bak"] {
        let path = temp_path(name);
        let error = save(&path, &image).unwrap_err();
        assert!(
            matches!(error, CaptureError::UnsupportedExtension { .. }),
            "{error:?}"
        );
        assert_names(&error, &path);
        assert!(matches!(
            load(&path).unwrap_err(),
            CaptureError::UnsupportedExtension { .. }
        ));
    }
}

#[test]
fn writing_into_a_missing_directory_names_the_path() {
    let image = ImageData::new(2, 2);
    for name in ["frame.exr", "frame.png"] {
        let path = temp_path("no_such_dir").join(name);
        let error = save(&path, &image).unwrap_err();
        assert!(matches!(error, CaptureError::Io { .. }), "{error:?}");
        assert_names(&error, &path);
    }
}

#[test]
fn empty_images_cannot_be_saved() {
    let image = ImageData::new(0, 4);
    for name in ["empty_image.exr", "empty_image.png"] {
        let path = temp_path(name);
        let error = save(&path, &image).unwrap_err();
        assert!(matches!(error, CaptureError::Encode { .. }), "{error:?}");
        assert!(!path.exists());
    }
}

#[test]
fn inconsistent_images_are_rejected_instead_of_panicking() {
    let mut image = ImageData::new(3, 3);
    image.pixels.truncate(4);
    for name in ["inconsistent.exr", "inconsistent.png"] {
        let path = temp_path(name);
        let error = save(&path, &image).unwrap_err();
        assert!(
            matches!(
                error,
                CaptureError::PixelCountMismatch {
                    expected: 9,
                    actual: 4,
                    ..
                }
            ),
            "{error:?}"
        );
    }
}
