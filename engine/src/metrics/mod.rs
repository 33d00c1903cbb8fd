//! Image-quality metrics over [`ImageData`](crate::capture::ImageData):
//! pure functions comparing a test image (or sequence) with a reference.
//!
//! Every function checks its inputs and returns a [`MetricsError`] instead of
//! panicking. Pixel-wise error metrics use the R, G and B channels and ignore
//! alpha. Non-finite pixel values propagate into the results; check
//! [`ImageData::has_non_finite`](crate::capture::ImageData::has_non_finite)
//! first where that matters.

mod check;
mod error;
mod flip;
mod flip_map;
mod instability_map;
mod light_map;
mod pixel_map;
mod pixelwise;
mod plane;
mod sequence;
mod ssim;
mod sum;
mod temporal;

pub use error::MetricsError;
pub use flip::{
    flip, hdr_flip, FlipReference, FlipResult, HdrFlipParams, DEFAULT_PIXELS_PER_DEGREE,
};
pub use flip_map::flip_map;
pub use instability_map::instability_map;
pub use light_map::light_map;
pub use pixel_map::{BrightnessBand, PixelMap};
pub use pixelwise::{max_abs_error, mean_per_channel, mse, psnr, rel_mse, DEFAULT_REL_MSE_EPSILON};
pub use sequence::{
    evaluate_frame, evaluate_sequence, evaluate_sequences, FrameMetrics, PreparedReference,
    SequenceMetrics,
};
pub use ssim::{dssim, ssim, SsimMode, SsimReference};
pub use temporal::{temporal_instability, TemporalInstability};
