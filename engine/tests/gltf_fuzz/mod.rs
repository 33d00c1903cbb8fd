//! Helpers of the glTF importer's property test (`scene_gltf_fuzz.rs`): the seed files, mutations
//! of their bytes and of their JSON, and an import that turns a panic or a hang into a failure.

pub mod bytes;
pub mod check;
pub mod corpus;
pub mod json;
