//! `cornell-box`: a transcription of Mitsuba 3's `mitsuba.cornell_box()`.
//!
//! Source: Mitsuba 3, `src/python/python/util.py`, function
//! `cornell_box()` ("Returns a dictionary containing a description of the
//! Cornell Box scene"). Every shape there is a `rectangle` (`[-1,1]²` at
//! `z = 0`, facing `+Z`) or a `cube` (`[-1,1]³`) with a `to_world`
//! transform, reproduced here as instances of one rectangle and one cube
//! mesh with the same transforms (translate · rotate · scale, rotations in
//! degrees about the given axis):
//!
//! | shape      | to_world                                                        | bsdf  |
//! |------------|-----------------------------------------------------------------|-------|
//! | light      | T(0, 0.99, 0.01) · R(x, 90) · S(0.23, 0.19, 0.19); radiance (18.387, 13.9873, 6.75357) | white |
//! | floor      | T(0, -1, 0) · R(x, -90)                                         | white |
//! | ceiling    | T(0, 1, 0) · R(x, 90)                                           | white |
//! | back       | T(0, 0, -1)                                                     | white |
//! | green-wall | T(1, 0, 0) · R(y, -90)                                          | green |
//! | red-wall   | T(-1, 0, 0) · R(y, 90)                                          | red   |
//! | small-box  | T(0.335, -0.7, 0.38) · R(y, -17) · S(0.3)                       | white |
//! | large-box  | T(-0.33, -0.4, -0.28) · R(y, 18.25) · S(0.3, 0.61, 0.3)         | white |
//!
//! Diffuse reflectances: white (0.885809, 0.698859, 0.666422), green
//! (0.105421, 0.37798, 0.076425), red (0.570068, 0.0430135, 0.0443706).
//! Sensor: perspective, `fov` 39.3077° on the smaller image axis (the
//! vertical one for square and landscape images), `look_at(origin = (0, 0,
//! 3.9), target = (0, 0, 0), up = (0, 1, 0))`. The light's BSDF is the
//! white diffuse, so its material is white diffuse plus emission.

use glam::{Affine3A, Quat, Vec3};

use super::paths;
use super::shapes;
use crate::scene::{Camera, Material, Scene, SceneError};

/// White diffuse reflectance.
pub const WHITE: Vec3 = Vec3::new(0.885809, 0.698859, 0.666422);
/// Green diffuse reflectance.
pub const GREEN: Vec3 = Vec3::new(0.105421, 0.37798, 0.076425);
/// Red diffuse reflectance.
pub const RED: Vec3 = Vec3::new(0.570068, 0.0430135, 0.0443706);
/// Radiance of the ceiling light.
pub const LIGHT_RADIANCE: Vec3 = Vec3::new(18.387, 13.9873, 6.75357);
/// Vertical field of view of the Mitsuba sensor, degrees.
pub const FOV_DEGREES: f32 = 39.3077;

fn trs(t: Vec3, axis: Vec3, degrees: f32, s: Vec3) -> Affine3A {
    Affine3A::from_translation(t)
        * Affine3A::from_quat(Quat::from_axis_angle(axis, degrees.to_radians()))
        * Affine3A::from_scale(s)
}

/// Material and mesh ids of the room, for scenes that extend it.
pub struct Room {
    /// White diffuse material.
    pub white: u32,
    /// The `[-1,1]³` cube mesh.
    pub cube: u32,
}

/// Adds the walls, floor, ceiling and light of the box (no boxes inside),
/// plus the Mitsuba camera and a gentle default camera path.
pub fn room(scene: &mut Scene) -> Room {
    let white = scene.add_material(Material::diffuse("white", WHITE));
    let green = scene.add_material(Material::diffuse("green", GREEN));
    let red = scene.add_material(Material::diffuse("red", RED));
    let light = scene.add_material(Material::diffuse("light", WHITE).with_emission(LIGHT_RADIANCE));
    let rect = scene.add_mesh(shapes::rectangle("rectangle", white));
    let cube = scene.add_mesh(shapes::cube("cube", white));
    let one = Vec3::ONE;
    let placements = [
        (
            trs(
                Vec3::new(0.0, 0.99, 0.01),
                Vec3::X,
                90.0,
                Vec3::new(0.23, 0.19, 0.19),
            ),
            light,
        ),
        (trs(Vec3::new(0.0, -1.0, 0.0), Vec3::X, -90.0, one), white),
        (trs(Vec3::new(0.0, 1.0, 0.0), Vec3::X, 90.0, one), white),
        (trs(Vec3::new(0.0, 0.0, -1.0), Vec3::X, 0.0, one), white),
        (trs(Vec3::new(1.0, 0.0, 0.0), Vec3::Y, -90.0, one), green),
        (trs(Vec3::new(-1.0, 0.0, 0.0), Vec3::Y, 90.0, one), red),
    ];
    for (m, mat) in placements {
        scene.add_instance(rect, m, Some(mat));
    }
    scene.camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y, FOV_DEGREES);
    scene.camera_path = Some(paths::sway(
        Vec3::new(0.0, 0.0, 3.9),
        Vec3::ZERO,
        FOV_DEGREES,
    ));
    Room { white, cube }
}

/// Builds `cornell-box`.
pub fn build() -> Result<Scene, SceneError> {
    let mut scene = Scene::new("cornell-box");
    let room = room(&mut scene);
    scene.add_instance(
        room.cube,
        trs(
            Vec3::new(0.335, -0.7, 0.38),
            Vec3::Y,
            -17.0,
            Vec3::splat(0.3),
        ),
        None,
    );
    scene.add_instance(
        room.cube,
        trs(
            Vec3::new(-0.33, -0.4, -0.28),
            Vec3::Y,
            18.25,
            Vec3::new(0.3, 0.61, 0.3),
        ),
        None,
    );
    scene.validate()?;
    Ok(scene)
}
