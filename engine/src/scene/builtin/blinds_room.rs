//! `blinds-room`: a closed room lit only from outside, by a sun and a sky
//! seen through one window covered by tilted blinds (one slat mesh,
//! instanced), so the sunlight falls into the room as stripes.

use glam::{Affine3A, Quat, Vec3};

use super::paths;
use super::shapes::{wall_with_openings, MeshBuilder};
use crate::scene::{Camera, Environment, Material, Scene, SceneError, Sun};

/// Builds `blinds-room`.
pub fn build() -> Result<Scene, SceneError> {
    let mut scene = Scene::new("blinds-room");
    let plaster = scene.add_material(Material::diffuse("plaster", Vec3::new(0.8, 0.78, 0.74)));
    let wood = scene.add_material(Material::diffuse("floor-wood", Vec3::new(0.45, 0.3, 0.18)));
    let slat = scene.add_material(Material::diffuse("slat", Vec3::splat(0.85)));
    let steel = scene.add_material(Material::conductor(
        "steel",
        Vec3::new(0.63, 0.62, 0.6),
        0.15,
    ));

    let mut walls = MeshBuilder::new();
    walls.quad(
        Vec3::new(-3.0, 3.0, -2.5),
        Vec3::X * 6.0,
        Vec3::Z * 5.0,
        1,
        1,
    );
    walls.quad(
        Vec3::new(-3.0, 0.0, 2.5),
        Vec3::NEG_Z * 5.0,
        Vec3::Y * 3.0,
        1,
        1,
    );
    walls.quad(
        Vec3::new(3.0, 0.0, -2.5),
        Vec3::Z * 5.0,
        Vec3::Y * 3.0,
        1,
        1,
    );
    walls.quad(
        Vec3::new(3.0, 0.0, 2.5),
        Vec3::NEG_X * 6.0,
        Vec3::Y * 3.0,
        1,
        1,
    );
    // Window x in [-1.2, 1.2], y in [0.9, 2.3] in the back wall (z = -2.5).
    wall_with_openings(
        &mut walls,
        Vec3::new(-3.0, 0.0, -2.5),
        Vec3::X * 6.0,
        Vec3::Y * 3.0,
        &[[0.3, 0.3, 0.7, 2.3 / 3.0]],
    );
    scene.add_mesh_instance(walls.build("walls", plaster));

    let mut floor = MeshBuilder::new();
    floor.quad(
        Vec3::new(-3.0, 0.0, 2.5),
        Vec3::X * 6.0,
        Vec3::NEG_Z * 5.0,
        1,
        1,
    );
    scene.add_mesh_instance(floor.build("floor", wood));

    let mut slat_mesh = MeshBuilder::new();
    slat_mesh.cuboid(
        Vec3::new(-1.25, -0.004, -0.035),
        Vec3::new(1.25, 0.004, 0.035),
        1,
    );
    let slat_id = scene.add_mesh(slat_mesh.build("slat", slat));
    for k in 0..28 {
        let y = 0.92 + 0.05 * k as f32;
        let m = Affine3A::from_rotation_translation(
            Quat::from_rotation_x(35f32.to_radians()),
            Vec3::new(0.0, y, -2.42),
        );
        scene.add_instance(slat_id, m, None);
    }

    let mut table = MeshBuilder::new();
    table.cuboid(Vec3::new(-0.8, 0.72, -0.45), Vec3::new(0.8, 0.76, 0.45), 1);
    for (x, z) in [(-0.75, -0.4), (0.75, -0.4), (-0.75, 0.4), (0.75, 0.4)] {
        table.cylinder(Vec3::new(x, 0.0, z), 0.03, 0.72, 16, 1);
    }
    let table = scene.add_mesh(table.build("table", steel));
    scene.add_instance(
        table,
        Affine3A::from_translation(Vec3::new(0.0, 0.0, -0.6)),
        None,
    );

    scene.sun = Some(Sun {
        direction: Vec3::new(0.35, 0.55, -1.0).normalize(),
        irradiance: Vec3::new(6.0, 5.6, 5.0),
        angular_radius: 0.00465,
    });
    scene.environment = Environment::Sky {
        zenith: Vec3::new(0.25, 0.4, 0.8),
        horizon: Vec3::new(0.7, 0.8, 0.95),
        ground: Vec3::new(0.2, 0.18, 0.15),
    };
    let eye = Vec3::new(2.2, 1.6, 2.0);
    let target = Vec3::new(-0.3, 1.1, -2.0);
    scene.camera = Camera::look_at(eye, target, Vec3::Y, 60.0);
    scene.camera_path = Some(paths::dolly(
        eye,
        Vec3::new(-1.8, 1.5, 1.8),
        target,
        60.0,
        6.0,
    ));
    scene.validate()?;
    Ok(scene)
}
