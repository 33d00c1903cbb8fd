//! `caustics`: a smooth glass sphere resting on a diffuse floor under a
//! small, bright area light, which focuses into a caustic on the floor.

use glam::{Affine3A, Quat, Vec3};

use super::{paths, shapes};
use crate::scene::{Camera, Material, Scene, SceneError};

/// Builds `caustics`.
pub fn build() -> Result<Scene, SceneError> {
    let mut scene = Scene::new("caustics");
    let floor = scene.add_material(Material::diffuse("floor", Vec3::splat(0.7)));
    let glass = scene.add_material(Material::dielectric("glass", 1.5, 0.0));
    let lamp = scene.add_material(Material::emissive("lamp", Vec3::splat(800.0)));
    let rect = scene.add_mesh(shapes::rectangle("rectangle", floor));
    scene.add_instance(
        rect,
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(3.0),
            Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2),
            Vec3::ZERO,
        ),
        None,
    );
    scene.add_instance(
        rect,
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(0.06),
            Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
            Vec3::new(0.4, 2.5, -0.2),
        ),
        Some(lamp),
    );
    scene.add_sphere(Vec3::new(0.0, 0.5, 0.0), 0.5, glass);
    let eye = Vec3::new(0.0, 1.6, 3.2);
    let target = Vec3::new(0.0, 0.3, 0.0);
    scene.camera = Camera::look_at(eye, target, Vec3::Y, 40.0);
    scene.camera_path = Some(paths::sway(eye, target, 40.0));
    scene.validate()?;
    Ok(scene)
}
