//! OpenEXR encoding and decoding through the `exr` crate.

use std::io::Cursor;
use std::path::Path;

use exr::error::Error as ExrError;
use exr::meta::header::Header;
use exr::meta::MetaData;
use exr::prelude::{
    f16, Blocks, Compression, Encoding, Image, LineOrder, ReadChannels, ReadLayers, RgbaChannels,
    SpecificChannels, Vec2, WritableImage,
};

use super::file::{read_file, write_file};
use super::{CaptureError, ImageData};

/// Sample type used for every channel of a written EXR file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ExrPrecision {
    /// 32-bit IEEE floats: lossless for [`ImageData`].
    #[default]
    F32,
    /// 16-bit half floats: about three significant decimal digits, values
    /// above 65504 become infinite.
    F16,
}

/// The block layout every written file uses: ZIP-compressed scan lines of 16
/// rows, top to bottom, which every EXR reader accepts.
const WRITE_ENCODING: Encoding = Encoding {
    compression: Compression::ZIP16,
    blocks: Blocks::ScanLines,
    line_order: LineOrder::Increasing,
};

/// Writes `image` to `path` as a single-layer RGBA EXR file with the given
/// sample precision.
pub fn save_exr(
    path: impl AsRef<Path>,
    image: &ImageData,
    precision: ExrPrecision,
) -> Result<(), CaptureError> {
    let path = path.as_ref();
    image.validate()?;
    let encode_error = |message: String| CaptureError::Encode {
        path: path.to_path_buf(),
        message,
    };
    if image.pixel_count() == 0 {
        return Err(encode_error("an EXR image needs at least one pixel".into()));
    }
    let bytes = encode(image, precision).map_err(|e| encode_error(e.to_string()))?;
    write_file(path, &bytes)
}

fn encode(image: &ImageData, precision: ExrPrecision) -> Result<Vec<u8>, ExrError> {
    let size = (image.width as usize, image.height as usize);
    let width = image.width as usize;
    let pixel = |pos: Vec2<usize>| image.pixels[pos.y() * width + pos.x()];
    let mut out = Cursor::new(Vec::new());
    match precision {
        ExrPrecision::F32 => {
            let channels = SpecificChannels::rgba(|pos| {
                let [r, g, b, a] = pixel(pos);
                (r, g, b, a)
            });
            Image::from_encoded_channels(size, WRITE_ENCODING, channels)
                .write()
                .to_buffered(&mut out)?;
        }
        ExrPrecision::F16 => {
            let channels = SpecificChannels::rgba(|pos| {
                let [r, g, b, a] = pixel(pos).map(f16::from_f32);
                (r, g, b, a)
            });
            Image::from_encoded_channels(size, WRITE_ENCODING, channels)
                .write()
                .to_buffered(&mut out)?;
        }
    }
    Ok(out.into_inner())
}

/// Reads the first layer with R, G and B channels of the EXR file at `path`,
/// at its largest resolution level. Samples of any type (half, float, uint)
/// are converted to `f32`; a missing A channel reads as 1.
pub fn load_exr(path: impl AsRef<Path>) -> Result<ImageData, CaptureError> {
    let path = path.as_ref();
    let bytes = read_file(path)?;
    decode(&bytes).map_err(|failure| failure.into_error(path))
}

/// Why decoding failed, before the path is attached.
enum DecodeFailure {
    Corrupt(String),
    Unsupported(String),
}

impl DecodeFailure {
    fn into_error(self, path: &Path) -> CaptureError {
        let path = path.to_path_buf();
        match self {
            DecodeFailure::Corrupt(message) => CaptureError::Decode { path, message },
            DecodeFailure::Unsupported(message) => {
                CaptureError::UnsupportedLayout { path, message }
            }
        }
    }
}

impl From<ExrError> for DecodeFailure {
    fn from(error: ExrError) -> Self {
        match error {
            ExrError::NotSupported(message) => DecodeFailure::Unsupported(message.into_owned()),
            other => DecodeFailure::Corrupt(other.to_string()),
        }
    }
}

fn has_rgb(header: &Header) -> bool {
    ["R", "G", "B"]
        .iter()
        .all(|name| header.channels.list.iter().any(|c| c.name == **name))
}

fn check_layout(bytes: &[u8]) -> Result<(), DecodeFailure> {
    let meta = MetaData::read_from_buffered(Cursor::new(bytes), false)?;
    if meta.headers.iter().any(|h| has_rgb(h) && !h.deep) {
        return Ok(());
    }
    let found: Vec<String> = meta
        .headers
        .iter()
        .flat_map(|h| h.channels.list.iter().map(|c| c.name.to_string()))
        .collect();
    Err(DecodeFailure::Unsupported(format!(
        "no flat layer has R, G and B channels (channels found: [{}])",
        found.join(", ")
    )))
}

fn decode(bytes: &[u8]) -> Result<ImageData, DecodeFailure> {
    check_layout(bytes)?;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size: Vec2<usize>, _: &RgbaChannels| {
                (size.x(), vec![[0.0, 0.0, 0.0, 1.0]; size.area()])
            },
            |(width, pixels): &mut (usize, Vec<[f32; 4]>),
             pos: Vec2<usize>,
             (r, g, b, a): (f32, f32, f32, f32)| {
                if let Some(pixel) = pixels.get_mut(pos.y() * *width + pos.x()) {
                    *pixel = [r, g, b, a];
                }
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))?;
    let size = image.layer_data.size;
    let (_, pixels) = image.layer_data.channel_data.pixels;
    let too_large =
        || DecodeFailure::Unsupported(format!("{}x{} is too large", size.x(), size.y()));
    let width = u32::try_from(size.x()).map_err(|_| too_large())?;
    let height = u32::try_from(size.y()).map_err(|_| too_large())?;
    ImageData::from_pixels(width, height, pixels).map_err(|e| DecodeFailure::Corrupt(e.to_string()))
}
