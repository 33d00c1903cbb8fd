//! Denoising: progressive accumulation while the view is still, SVGF, the learned recurrent
//! denoiser, the temporal denoisers' still-camera hand-off to the accumulation, the G-buffer they
//! read and the emission they add back, supersampled at emitters' edges.

pub mod accumulate;
mod atrous_tile;
pub mod edge_emission;
mod frame_denoiser;
pub mod gbuffer;
pub mod handoff;
pub mod neural;
pub mod svgf;

pub use frame_denoiser::{DenoiseInputs, Denoised, FrameDenoiser, FrameInfo, TransportRequest};
