//! Denoising: progressive accumulation while the view is still, SVGF, the learned recurrent
//! denoiser, and the G-buffer they read.

pub mod accumulate;
mod frame_denoiser;
pub mod gbuffer;
pub mod neural;
pub mod svgf;

pub use frame_denoiser::{DenoiseInputs, Denoised, FrameDenoiser, FrameInfo, TransportRequest};
