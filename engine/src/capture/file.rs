//! Format selection by file extension, and the file I/O shared by the
//! format modules.

use std::path::Path;

use super::{
    load_exr, load_png, save_exr, save_png, CaptureError, ExrPrecision, ImageData, PngEncoding,
};

/// The formats [`save`] and [`load`] pick between.
enum Format {
    Exr,
    Png,
}

fn format_of(path: &Path) -> Result<Format, CaptureError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("exr") => Ok(Format::Exr),
        Some("png") => Ok(Format::Png),
        _ => Err(CaptureError::UnsupportedExtension {
            path: path.to_path_buf(),
        }),
    }
}

/// Saves `image` in the format named by the extension of `path`
/// (case-insensitive): `.exr` as 32-bit float EXR, `.png` as 8-bit PNG with
/// the default [`PngEncoding`] (0 EV, clamp, sRGB).
pub fn save(path: impl AsRef<Path>, image: &ImageData) -> Result<(), CaptureError> {
    let path = path.as_ref();
    match format_of(path)? {
        Format::Exr => save_exr(path, image, ExrPrecision::F32),
        Format::Png => save_png(path, image, &PngEncoding::default()),
    }
}

/// Loads the image at `path` in the format named by its extension
/// (case-insensitive `.exr` or `.png`) as linear RGBA.
pub fn load(path: impl AsRef<Path>) -> Result<ImageData, CaptureError> {
    let path = path.as_ref();
    match format_of(path)? {
        Format::Exr => load_exr(path),
        Format::Png => load_png(path),
    }
}

/// Reads a whole file, naming `path` in the error.
pub(super) fn read_file(path: &Path) -> Result<Vec<u8>, CaptureError> {
    std::fs::read(path).map_err(|source| CaptureError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Writes a whole file atomically (the old file stays if writing fails), naming `path` in the
/// error.
pub(super) fn write_file(path: &Path, bytes: &[u8]) -> Result<(), CaptureError> {
    crate::atomic_write::write_atomic(path, bytes).map_err(|source| CaptureError::Io {
        path: path.to_path_buf(),
        source,
    })
}
