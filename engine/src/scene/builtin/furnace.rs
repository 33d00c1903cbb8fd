//! `furnace`: the white-furnace test. A single Lambertian analytic sphere
//! of albedo 0.8 inside a uniform environment of radiance 1. The expected
//! image is known in closed form: every pixel that sees the environment is
//! 1 and every pixel that sees the sphere is `0.8 · 1` (see
//! [`crate::scene::Scene::analytic_radiance`]): the sphere is convex, so all
//! scattered light comes straight from the environment and multiple
//! bounces change nothing.

use glam::Vec3;

use super::paths;
use crate::scene::{Camera, Environment, Material, Scene, SceneError};

/// Albedo of the furnace sphere.
pub const ALBEDO: f32 = 0.8;
/// Environment radiance.
pub const RADIANCE: f32 = 1.0;

/// Builds `furnace`.
pub fn build() -> Result<Scene, SceneError> {
    let mut scene = Scene::new("furnace");
    let grey = scene.add_material(Material::diffuse("albedo-0.8", Vec3::splat(ALBEDO)));
    scene.add_sphere(Vec3::ZERO, 1.0, grey);
    scene.environment = Environment::Constant(Vec3::splat(RADIANCE));
    let eye = Vec3::new(0.0, 0.0, 4.0);
    scene.camera = Camera::look_at(eye, Vec3::ZERO, Vec3::Y, 40.0);
    scene.camera_path = Some(paths::sway(eye, Vec3::ZERO, 40.0));
    scene.validate()?;
    Ok(scene)
}
