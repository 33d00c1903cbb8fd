//! Passes for looking inside a frame and for testing the engine: debug views of intermediate
//! images, a test pattern with a known output, batch ray queries, the shaders' ways of rounding
//! to half precision and the BSDFs' sampling against their evaluation.

pub mod bsdf_sampling;
pub mod debug_view;
pub mod half_rounding;
pub mod ray_query;
pub mod test_pattern;
