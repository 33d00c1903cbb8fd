//! 8-bit sRGB PNG encoding and decoding through the `image` crate.

use std::path::Path;

use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder, ImageError, ImageFormat};

use super::file::{read_file, write_file};
use super::{srgb_decode, CaptureError, ImageData, PngEncoding};

/// Writes `image` to `path` as an 8-bit RGBA PNG, display-encoded with
/// `encoding` (exposure, tone curve, sRGB OETF); alpha is always 255.
pub fn save_png(
    path: impl AsRef<Path>,
    image: &ImageData,
    encoding: &PngEncoding,
) -> Result<(), CaptureError> {
    let path = path.as_ref();
    image.validate()?;
    let bytes: Vec<u8> = image
        .pixels
        .iter()
        .flat_map(|&p| encoding.encode_pixel(p).map(quantize))
        .collect();
    let mut out = Vec::new();
    PngEncoder::new(&mut out)
        .write_image(&bytes, image.width, image.height, ExtendedColorType::Rgba8)
        .map_err(|e| CaptureError::Encode {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    write_file(path, &out)
}

fn quantize(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Reads the PNG at `path` (any bit depth or colour type) as linear RGBA:
/// colour channels are decoded from sRGB, alpha is kept as stored, and grey
/// or alpha-less images expand to RGBA with alpha 1.
pub fn load_png(path: impl AsRef<Path>) -> Result<ImageData, CaptureError> {
    let path = path.as_ref();
    let bytes = read_file(path)?;
    let decoded = image::load_from_memory_with_format(&bytes, ImageFormat::Png)
        .map_err(|e| decode_error(path, e))?
        .into_rgba32f();
    let (width, height) = decoded.dimensions();
    let pixels = decoded
        .pixels()
        .map(|p| {
            let [r, g, b, a] = p.0;
            [srgb_decode(r), srgb_decode(g), srgb_decode(b), a]
        })
        .collect();
    ImageData::from_pixels(width, height, pixels).map_err(|e| CaptureError::Decode {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

fn decode_error(path: &Path, error: ImageError) -> CaptureError {
    let path = path.to_path_buf();
    let message = error.to_string();
    match error {
        ImageError::Unsupported(_) | ImageError::Limits(_) => {
            CaptureError::UnsupportedLayout { path, message }
        }
        _ => CaptureError::Decode { path, message },
    }
}
