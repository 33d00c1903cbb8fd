//! The error type of the capture module.

use std::path::PathBuf;

/// Everything that can go wrong while building, saving or loading an image.
#[derive(Debug, thiserror::Error)]
pub enum CaptureError {
    /// A pixel buffer's length does not match `width * height`.
    #[error("pixel buffer holds {actual} pixels but a {width}x{height} image needs {expected}")]
    PixelCountMismatch {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// `width * height`, or `usize::MAX` when that overflows.
        expected: usize,
        /// Length of the buffer that was supplied.
        actual: usize,
    },
    /// The file name has no extension this module knows (`.exr`, `.png`).
    #[error("{}: unsupported image extension (expected .exr or .png)", path.display())]
    UnsupportedExtension {
        /// The offending path.
        path: PathBuf,
    },
    /// Reading or writing the file itself failed.
    #[error("{}: I/O error: {source}", path.display())]
    Io {
        /// The file being read or written.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The image cannot be stored in the requested format.
    #[error("{}: cannot encode image: {message}", path.display())]
    Encode {
        /// The file being written.
        path: PathBuf,
        /// What the encoder reported.
        message: String,
    },
    /// The file's contents are not a valid image of the expected format.
    #[error("{}: invalid or corrupt image data: {message}", path.display())]
    Decode {
        /// The file being read.
        path: PathBuf,
        /// What the decoder reported.
        message: String,
    },
    /// The file is a valid image, but laid out in a way this module does not
    /// read (for example an EXR without R, G and B channels, or deep data).
    #[error("{}: unsupported image layout: {message}", path.display())]
    UnsupportedLayout {
        /// The file being read.
        path: PathBuf,
        /// What is unsupported.
        message: String,
    },
}
