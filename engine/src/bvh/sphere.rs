//! Analytic spheres, the second primitive type.

use glam::Vec3;

/// A world-space analytic sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius, `> 0`.
    pub radius: f32,
    /// Index into `Scene::materials`.
    pub material: u32,
}
