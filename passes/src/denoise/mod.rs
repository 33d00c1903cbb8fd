//! Denoising: progressive accumulation while the view is still, SVGF, the learned recurrent
//! denoiser, and the G-buffer they read.

pub mod accumulate;
pub mod gbuffer;
pub mod neural;
pub mod svgf;
