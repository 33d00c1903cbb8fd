//! Post-processing of the finished HDR image.

pub mod tonemap;
