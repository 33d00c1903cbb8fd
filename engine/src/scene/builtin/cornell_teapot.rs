//! `cornell-teapot`: the Mitsuba Cornell box (without its two boxes) with
//! three instances of one tessellated Utah teapot: diffuse, smooth glass
//! and rough coloured metal (instance material overrides).

use glam::{Affine3A, Quat, Vec3};

use super::{cornell_box, teapot, BuildOptions};
use crate::scene::{Material, Scene, SceneError};

/// Builds `cornell-teapot`; `detail` scales the patch tessellation
/// (16 x 16 quads per patch at full detail, about 16 k triangles).
pub fn build(options: &BuildOptions) -> Result<Scene, SceneError> {
    let mut scene = Scene::new("cornell-teapot");
    cornell_box::room(&mut scene);
    let diffuse = scene.add_material(Material::diffuse(
        "teapot-diffuse",
        Vec3::new(0.8, 0.78, 0.7),
    ));
    let glass = scene.add_material(Material::dielectric("teapot-glass", 1.5, 0.0));
    let metal = scene.add_material(Material::conductor(
        "teapot-copper",
        Vec3::new(0.955, 0.638, 0.538),
        0.05,
    ));
    let divs = ((16.0 * options.detail.sqrt()).round() as u32).clamp(2, 64);
    let pot = scene.add_mesh(teapot::teapot("teapot", diffuse, divs));
    let place = |x: f32, z: f32, degrees: f32| {
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(0.1),
            Quat::from_rotation_y(degrees.to_radians()),
            Vec3::new(x, -1.0, z),
        )
    };
    scene.add_instance(pot, place(-0.5, -0.35, 30.0), None);
    scene.add_instance(pot, place(0.5, -0.35, -30.0), Some(metal));
    scene.add_instance(pot, place(0.0, 0.35, 10.0), Some(glass));
    scene.validate()?;
    Ok(scene)
}
