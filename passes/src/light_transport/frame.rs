//! The image and sampling of a frame, as the light-transport passes take them.

use crate::samples_per_pixel::SamplesPerPixel;

/// The image and sampling of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Samples per pixel (camera samples for BDPT).
    pub samples_per_pixel: SamplesPerPixel,
    /// Longest path in segments (Mitsuba's convention).
    pub max_depth: u32,
    /// Write the denoiser's images too ([`crate::light_transport::SurfaceImages`]).
    pub surface: bool,
}
