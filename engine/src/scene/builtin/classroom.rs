//! `classroom`: a 12 m x 10 m room with 30 instanced desks and chairs
//! (≥ 500 k triangles after instancing at full detail), lit by the sky and
//! sun through three windows and by six emissive ceiling panels. Desk tops
//! carry a procedural wood-grain texture.

use glam::{Affine3A, Quat, Vec3};

use super::shapes::{self, wall_with_openings, MeshBuilder};
use super::{paths, BuildOptions};
use crate::scene::{
    Camera, Environment, Material, Scene, SceneError, Sun, TexelData, Texture, TextureRef,
};

fn wood_texture() -> Texture {
    let size = 64u32;
    let texels = (0..size * size)
        .map(|i| {
            let (x, y) = ((i % size) as f32, (i / size) as f32);
            let ring = ((x * 0.35 + (y * 0.21).sin() * 2.0).sin() * 0.5 + 0.5) * 40.0;
            [
                (150.0 + ring) as u8,
                (100.0 + ring * 0.6) as u8,
                (60.0 + ring * 0.3) as u8,
                255,
            ]
        })
        .collect();
    Texture {
        name: "wood".into(),
        width: size,
        height: size,
        srgb: true,
        texels: TexelData::Rgba8(texels),
    }
}

/// Builds `classroom`; `detail` scales the tessellation of desks and chairs.
pub fn build(options: &BuildOptions) -> Result<Scene, SceneError> {
    let mut scene = Scene::new("classroom");
    let q = options.detail.clamp(1e-4, 1.0).sqrt();
    let res = |full: f32, min: u32| ((full * q).round() as u32).max(min);

    let wall = scene.add_material(Material::diffuse("wall", Vec3::new(0.78, 0.76, 0.7)));
    let floor_mat = scene.add_material(Material::diffuse("linoleum", Vec3::new(0.35, 0.33, 0.3)));
    let board = scene.add_material(Material::diffuse("blackboard", Vec3::new(0.05, 0.12, 0.08)));
    let wood_tex = scene.add_texture(wood_texture());
    let mut wood = Material::diffuse("desk-wood", Vec3::ONE);
    wood.base_color_texture = Some(TextureRef::new(wood_tex));
    let wood = scene.add_material(wood);
    let steel = scene.add_material(Material::conductor(
        "steel",
        Vec3::new(0.63, 0.62, 0.6),
        0.2,
    ));
    let plastic = scene.add_material(Material::diffuse(
        "chair-plastic",
        Vec3::new(0.1, 0.25, 0.55),
    ));
    let panel = scene.add_material(Material::emissive(
        "ceiling-panel",
        Vec3::new(12.0, 11.5, 10.5),
    ));

    let mut room = MeshBuilder::new();
    room.quad(
        Vec3::new(-6.0, 3.2, -5.0),
        Vec3::X * 12.0,
        Vec3::Z * 10.0,
        1,
        1,
    );
    room.quad(
        Vec3::new(6.0, 0.0, -5.0),
        Vec3::Z * 10.0,
        Vec3::Y * 3.2,
        1,
        1,
    );
    room.quad(
        Vec3::new(6.0, 0.0, 5.0),
        Vec3::NEG_X * 12.0,
        Vec3::Y * 3.2,
        1,
        1,
    );
    room.quad(
        Vec3::new(-6.0, 0.0, -5.0),
        Vec3::X * 12.0,
        Vec3::Y * 3.2,
        1,
        1,
    );
    wall_with_openings(
        &mut room,
        Vec3::new(-6.0, 0.0, 5.0),
        Vec3::NEG_Z * 10.0,
        Vec3::Y * 3.2,
        &[
            [0.1, 0.3, 0.28, 0.85],
            [0.41, 0.3, 0.59, 0.85],
            [0.72, 0.3, 0.9, 0.85],
        ],
    );
    scene.add_mesh_instance(room.build("room", wall));
    let mut floor = MeshBuilder::new();
    floor.quad(
        Vec3::new(-6.0, 0.0, 5.0),
        Vec3::X * 12.0,
        Vec3::NEG_Z * 10.0,
        1,
        1,
    );
    scene.add_mesh_instance(floor.build("floor", floor_mat));
    let mut blackboard = MeshBuilder::new();
    blackboard.cuboid(Vec3::new(-3.0, 0.9, -5.0), Vec3::new(3.0, 2.3, -4.97), 1);
    scene.add_mesh_instance(blackboard.build("blackboard", board));

    let mut top = MeshBuilder::new();
    top.cuboid(
        Vec3::new(-0.6, 0.72, -0.3),
        Vec3::new(0.6, 0.76, 0.3),
        res(24.0, 1),
    );
    let desk_top = scene.add_mesh(top.build("desk-top", wood));
    let mut legs = MeshBuilder::new();
    for (x, z) in [(-0.55, -0.25), (0.55, -0.25), (-0.55, 0.25), (0.55, 0.25)] {
        legs.cylinder(
            Vec3::new(x, 0.0, z),
            0.025,
            0.72,
            res(40.0, 6),
            res(20.0, 1),
        );
    }
    let desk_legs = scene.add_mesh(legs.build("desk-legs", steel));
    let mut seat = MeshBuilder::new();
    seat.cuboid(
        Vec3::new(-0.22, 0.42, -0.22),
        Vec3::new(0.22, 0.46, 0.22),
        res(16.0, 1),
    );
    seat.cuboid(
        Vec3::new(-0.22, 0.46, 0.19),
        Vec3::new(0.22, 0.9, 0.22),
        res(16.0, 1),
    );
    let chair_seat = scene.add_mesh(seat.build("chair-seat", plastic));
    let mut chair_legs = MeshBuilder::new();
    for (x, z) in [(-0.19, -0.19), (0.19, -0.19), (-0.19, 0.19), (0.19, 0.19)] {
        chair_legs.cylinder(
            Vec3::new(x, 0.0, z),
            0.018,
            0.42,
            res(32.0, 6),
            res(16.0, 1),
        );
    }
    let chair_legs = scene.add_mesh(chair_legs.build("chair-legs", steel));

    for row in 0..5 {
        for col in 0..6 {
            let x = -4.0 + 1.6 * col as f32;
            let z = -2.2 + 1.4 * row as f32;
            let turn = Quat::from_rotation_y(((row * 6 + col) % 5) as f32 * 2.0f32.to_radians());
            let desk = Affine3A::from_rotation_translation(turn, Vec3::new(x, 0.0, z));
            let chair = Affine3A::from_rotation_translation(turn, Vec3::new(x, 0.0, z + 0.55));
            scene.add_instance(desk_top, desk, None);
            scene.add_instance(desk_legs, desk, None);
            scene.add_instance(chair_seat, chair, None);
            scene.add_instance(chair_legs, chair, None);
        }
    }
    let teacher = Affine3A::from_scale_rotation_translation(
        Vec3::new(1.4, 1.0, 1.2),
        Quat::IDENTITY,
        Vec3::new(0.0, 0.0, -3.8),
    );
    scene.add_instance(desk_top, teacher, None);
    scene.add_instance(desk_legs, teacher, None);

    let rect = scene.add_mesh(shapes::rectangle("ceiling-panel", panel));
    for k in 0..6 {
        let x = -3.0 + 3.0 * (k % 3) as f32;
        let z = -2.0 + 4.0 * (k / 3) as f32;
        let m = Affine3A::from_scale_rotation_translation(
            Vec3::new(0.6, 0.15, 1.0),
            Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
            Vec3::new(x, 3.19, z),
        );
        scene.add_instance(rect, m, None);
    }

    scene.sun = Some(Sun {
        direction: Vec3::new(-1.0, 0.8, 0.3).normalize(),
        irradiance: Vec3::new(5.0, 4.7, 4.2),
        angular_radius: 0.00465,
    });
    scene.environment = Environment::Sky {
        zenith: Vec3::new(0.25, 0.4, 0.8),
        horizon: Vec3::new(0.7, 0.8, 0.95),
        ground: Vec3::new(0.2, 0.18, 0.15),
    };
    let eye = Vec3::new(5.0, 1.7, 4.6);
    let target = Vec3::new(-1.5, 1.0, -3.0);
    scene.camera = Camera::look_at(eye, target, Vec3::Y, 55.0);
    scene.camera_path = Some(paths::dolly(
        eye,
        Vec3::new(-4.5, 1.8, 4.4),
        target,
        55.0,
        8.0,
    ));
    scene.validate()?;
    Ok(scene)
}
