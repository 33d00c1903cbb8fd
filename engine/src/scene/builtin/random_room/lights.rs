//! Area lights: emissive panels under the ceiling or on a side wall, and
//! glowing boxes hanging below the ceiling.

use glam::{Affine3A, Quat, Vec2, Vec3};

use super::materials::light_tint;
use super::placement::{Obstacle, SharedMeshes};
use super::rng::Rng;
use super::room::Room;
use crate::scene::builtin::shapes::MeshBuilder;
use crate::scene::{Material, Scene};

/// Brightest and dimmest emitted radiance of a light.
const RADIANCE_RANGE: (f32, f32) = (5.0, 400.0);

/// Where a light is and what shape it has.
enum Fixture {
    /// A one-sided quad `corner + u*e1 + v*e2` facing `e1 x e2`.
    Panel { corner: Vec3, e1: Vec3, e2: Vec3 },
    /// An axis-aligned box.
    Box { center: Vec3, half: Vec3 },
}

impl Fixture {
    fn random(rng: &mut Rng, room: &Room) -> Self {
        let (a, b, h) = (room.half.x, room.half.y, room.height);
        match rng.weighted(&[0.5, 0.25, 0.25]) {
            0 => {
                let size = Vec2::new(rng.range(0.4, 1.5), rng.range(0.4, 1.5));
                let reach = room.half - size * 0.5 - 0.1;
                let c = Vec2::new(rng.range(-reach.x, reach.x), rng.range(-reach.y, reach.y));
                Fixture::Panel {
                    corner: Vec3::new(c.x - 0.5 * size.x, h - 0.01, c.y - 0.5 * size.y),
                    e1: Vec3::X * size.x,
                    e2: Vec3::Z * size.y,
                }
            }
            1 => {
                let (width, tall) = (rng.range(0.4, 1.2), rng.range(0.2, 0.8));
                let z0 = rng.range(-b + 0.2, b - 0.2 - width);
                let y0 = rng.range(0.8, h - 0.3 - tall);
                let (along, up) = (Vec3::Z * width, Vec3::Y * tall);
                if rng.chance(0.5) {
                    Fixture::Panel {
                        corner: Vec3::new(a - 0.01, y0, z0),
                        e1: along,
                        e2: up,
                    }
                } else {
                    Fixture::Panel {
                        corner: Vec3::new(-a + 0.01, y0, z0),
                        e1: up,
                        e2: along,
                    }
                }
            }
            _ => {
                let half = Vec3::new(
                    rng.range(0.1, 0.3),
                    rng.range(0.05, 0.2),
                    rng.range(0.1, 0.3),
                );
                let reach = room.half - Vec2::new(half.x, half.z) - 0.2;
                Fixture::Box {
                    center: Vec3::new(
                        rng.range(-reach.x, reach.x),
                        h - rng.range(0.2, 0.6) - half.y,
                        rng.range(-reach.y, reach.y),
                    ),
                    half,
                }
            }
        }
    }

    fn area(&self) -> f32 {
        match *self {
            Fixture::Panel { e1, e2, .. } => e1.cross(e2).length(),
            Fixture::Box { half: s, .. } => 8.0 * (s.x * s.y + s.y * s.z + s.z * s.x),
        }
    }

    /// Adds the fixture; a box also becomes an obstacle.
    fn add(
        &self,
        scene: &mut Scene,
        meshes: &mut SharedMeshes,
        material: u32,
        obstacles: &mut Vec<Obstacle>,
    ) {
        match *self {
            Fixture::Panel { corner, e1, e2 } => {
                let mut panel = MeshBuilder::new();
                panel.quad(corner, e1, e2, 1, 1);
                let name = scene.materials[material as usize].name.clone();
                scene.add_mesh_instance(panel.build(&name, material));
            }
            Fixture::Box { center, half } => {
                let cube = meshes.cube(scene, material);
                let transform =
                    Affine3A::from_scale_rotation_translation(half, Quat::IDENTITY, center);
                scene.add_instance(cube, transform, Some(material));
                obstacles.push(Obstacle {
                    center: Vec2::new(center.x, center.z),
                    radius: Vec2::new(half.x, half.z).length(),
                    bottom: center.y - half.y,
                    top: center.y + half.y,
                });
            }
        }
    }
}

/// Adds one to three area lights, or up to two when the room has windows
/// (so some rooms are lit only by the sun and sky), sharing a random total
/// power that grows with the room's surface; returns the hanging boxes as
/// obstacles.
pub fn add(
    scene: &mut Scene,
    rng: &mut Rng,
    room: &Room,
    windows: bool,
    meshes: &mut SharedMeshes,
) -> Vec<Obstacle> {
    let count = if windows {
        rng.int(0, 2)
    } else {
        rng.int(1, 3)
    };
    let power = rng.range(0.3, 1.0) * room.surface_area();
    let mut obstacles = Vec::new();
    for k in 0..count {
        let fixture = Fixture::random(rng, room);
        let radiance = (power / count as f32 / (std::f32::consts::PI * fixture.area()))
            .clamp(RADIANCE_RANGE.0, RADIANCE_RANGE.1);
        let light = Material::emissive(&format!("light-{k}"), light_tint(rng) * radiance);
        let material = scene.add_material(light);
        fixture.add(scene, meshes, material, &mut obstacles);
    }
    obstacles
}
