//! Mesh instances.

use glam::Affine3A;

/// One placement of a mesh in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Name used in messages.
    pub name: String,
    /// Index into `Scene::meshes`.
    pub mesh: u32,
    /// Object-to-world transform.
    pub transform: Affine3A,
    /// Material override (index into `Scene::materials`); `None` uses the
    /// mesh's own material.
    pub material: Option<u32>,
}
