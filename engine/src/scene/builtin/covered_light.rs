//! `covered-light`: the Mitsuba Cornell box whose ceiling light is covered
//! from below by a white panel, so light reaches the room only after
//! bouncing off the ceiling and the panel's top; a displaced high-poly
//! sphere (≥ 5 M triangles at full detail) and one analytic sphere.

use glam::{Affine3A, Vec3};

use super::{cornell_box, displaced_sphere, BuildOptions};
use crate::scene::{Material, Scene, SceneError};

/// Triangles of the high-poly mesh at `detail = 1`.
const FULL_TRIANGLES: u32 = 5_000_000;

/// Builds `covered-light`.
pub fn build(options: &BuildOptions) -> Result<Scene, SceneError> {
    let mut scene = Scene::new("covered-light");
    let room = cornell_box::room(&mut scene);
    // The light spans x ±0.23, z 0.01 ± 0.19 at y = 0.99; the panel
    // overhangs it by 0.07 on every side, 0.09 below the ceiling.
    scene.add_instance(
        room.cube,
        Affine3A::from_translation(Vec3::new(0.0, 0.9, 0.01))
            * Affine3A::from_scale(Vec3::new(0.3, 0.01, 0.26)),
        None,
    );
    let clay = scene.add_material(Material::diffuse("clay", Vec3::new(0.75, 0.6, 0.45)));
    let budget = (FULL_TRIANGLES as f64 * options.detail.clamp(1e-6, 1.0) as f64) / 12.0;
    let n = (budget.sqrt().ceil() as u32).max(2);
    let blob = scene.add_mesh(displaced_sphere::displaced_sphere(
        "displaced-sphere",
        clay,
        0.32,
        n,
    ));
    scene.add_instance(
        blob,
        Affine3A::from_translation(Vec3::new(-0.4, -0.62, -0.25)),
        None,
    );
    let chrome = scene.add_material(Material::conductor("chrome", Vec3::splat(0.9), 0.02));
    scene.add_sphere(Vec3::new(0.45, -0.7, 0.25), 0.3, chrome);
    scene.validate()?;
    Ok(scene)
}
