//! Scene description: meshes, spheres, instances, materials, textures,
//! lights, cameras and camera paths, plus glTF import, built-in scenes, the
//! two-level BVH built over a scene and the packed GPU layout.

mod alias;
pub mod builtin;
mod bvh;
mod camera;
mod camera_path;
pub mod environment_map;
mod error;
mod features;
mod flatten;
pub mod gltf_import;
pub mod gpu;
mod instance;
mod light;
mod light_list;
mod material;
mod mesh;
mod model;
mod tangents;
mod texture;
mod texture_ref;

pub use crate::bvh::Sphere;
pub use alias::{AliasEntry, AliasTable};
pub use bvh::{Bvh, BvhInstance, InstanceSource};
pub use camera::{look_rotation, Camera};
pub use camera_path::{CameraKey, CameraPath, PathInterpolation};
pub use environment_map::EnvironmentDistribution;
pub use error::SceneError;
pub use features::SceneFeatures;
pub use flatten::{FlatScene, Placement};
pub use gltf_import::{load_gltf, load_gltf_slice};
pub use instance::Instance;
pub use light::{luminance, Environment, PunctualLight, Sun, LUMENS_PER_WATT};
pub use light_list::{
    selection_power, LightDistribution, LightEntry, LightSource, Selection, UNIFORM_SELECTION,
};
pub use material::{AlphaMode, Material, MaterialKind, SMOOTH_ALPHA};
pub use mesh::Mesh;
pub use model::{AnalyticRadiance, Scene};
pub use texture::{TexelData, Texture};
pub use texture_ref::{TextureRef, UvTransform, WrapMode};
