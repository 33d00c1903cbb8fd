//! Frame capture: an in-memory linear RGBA image type and its EXR / PNG
//! encoders and decoders.
//!
//! [`ImageData`] holds linear, scene-referred RGBA floats. EXR files keep them
//! as they are (32- or 16-bit floats); PNG files store them display-referred:
//! exposed, tone-mapped, sRGB-encoded and quantised to 8 bits (see
//! [`PngEncoding`]).

mod error;
mod exr_io;
mod file;
mod image_data;
mod png_io;
mod srgb;
mod tone;
#[cfg(feature = "clap")]
mod tone_value_enum;

pub use error::CaptureError;
pub use exr_io::{load_exr, save_exr, ExrPrecision};
pub use file::{load, save};
pub use image_data::{rec709_luminance, ImageData};
pub use png_io::{load_png, save_png};
pub use srgb::{srgb_decode, srgb_encode};
pub use tone::{PngEncoding, ToneCurve};
