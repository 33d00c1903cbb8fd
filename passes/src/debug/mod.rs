//! Passes for looking inside a frame and for testing the engine: debug views of intermediate
//! images, a test pattern with a known output, and batch ray queries.

pub mod debug_view;
pub mod ray_query;
pub mod test_pattern;
