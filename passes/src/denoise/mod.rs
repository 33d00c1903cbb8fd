//! Denoising: progressive accumulation while the view is still, SVGF, and the G-buffer they read.

pub mod accumulate;
pub mod gbuffer;
pub mod svgf;
