//! The objects in the room: cuboids, spheres, cylinders and now and then a
//! teapot, standing on the floor or on top of a cuboid, each with its own
//! random material.

use glam::{Affine3A, Quat, Vec2, Vec3};

use super::materials::object_material;
use super::placement::{Obstacle, SharedMeshes};
use super::rng::Rng;
use super::room::Room;
use crate::scene::Scene;

/// Footprint radius of the teapot per unit of scale (its spout reaches
/// `x = 3.43`).
const TEAPOT_RADIUS: f32 = 3.5;
/// Height of the teapot per unit of scale.
const TEAPOT_HEIGHT: f32 = 3.15;

/// An object's shape and size.
enum Shape {
    Cuboid { half: Vec3 },
    Sphere { radius: f32 },
    Cylinder { radius: f32, height: f32 },
    Teapot { scale: f32 },
}

impl Shape {
    fn random(rng: &mut Rng) -> Self {
        match rng.weighted(&[0.35, 0.3, 0.25, 0.1]) {
            0 => Shape::Cuboid {
                half: Vec3::new(
                    rng.range(0.1, 0.6),
                    rng.range(0.1, 0.75),
                    rng.range(0.1, 0.6),
                ),
            },
            1 => Shape::Sphere {
                radius: rng.range(0.1, 0.5),
            },
            2 => Shape::Cylinder {
                radius: rng.range(0.08, 0.4),
                height: rng.range(0.2, 1.4),
            },
            _ => Shape::Teapot {
                scale: rng.range(0.06, 0.16),
            },
        }
    }

    /// Radius of the footprint (whatever the rotation) and height.
    fn extent(&self) -> (f32, f32) {
        match *self {
            Shape::Cuboid { half } => (Vec2::new(half.x, half.z).length(), 2.0 * half.y),
            Shape::Sphere { radius } => (radius, 2.0 * radius),
            Shape::Cylinder { radius, height } => (radius, height),
            Shape::Teapot { scale } => (TEAPOT_RADIUS * scale, TEAPOT_HEIGHT * scale),
        }
    }

    /// Adds the shape standing on `base`, turned by `yaw` about `+Y`.
    fn add(
        &self,
        scene: &mut Scene,
        meshes: &mut SharedMeshes,
        base: Vec3,
        yaw: f32,
        material: u32,
    ) {
        let place = |scale: Vec3, lift: f32| {
            Affine3A::from_scale_rotation_translation(
                scale,
                Quat::from_rotation_y(yaw),
                base + Vec3::Y * lift,
            )
        };
        let (mesh, transform) = match *self {
            Shape::Sphere { radius } => {
                scene.add_sphere(base + Vec3::Y * radius, radius, material);
                return;
            }
            Shape::Cuboid { half } => (meshes.cube(scene, material), place(half, half.y)),
            Shape::Cylinder { radius, height } => (
                meshes.cylinder(scene, material),
                place(Vec3::new(radius, height, radius), 0.0),
            ),
            Shape::Teapot { scale } => (
                meshes.teapot(scene, material),
                place(Vec3::splat(scale), 0.0),
            ),
        };
        scene.add_instance(mesh, transform, Some(material));
    }
}

/// The top of a cuboid, where one more object may stand.
struct Shelf {
    center: Vec2,
    height: f32,
    /// Radius of the circle inscribed in the top face.
    radius: f32,
}

/// Adds 4 to 16 objects (fewer when a small room has no space left),
/// avoiding `obstacles` and each other, and appends them to `obstacles`.
pub fn add(
    scene: &mut Scene,
    rng: &mut Rng,
    room: &Room,
    obstacles: &mut Vec<Obstacle>,
    meshes: &mut SharedMeshes,
) {
    let mut shelves = Vec::new();
    for index in 0..rng.int(4, 16) {
        let shape = Shape::random(rng);
        let (radius, height) = shape.extent();
        let Some(base) = place(rng, room, obstacles, &mut shelves, radius, height) else {
            continue;
        };
        let material = scene.add_material(object_material(rng, index));
        shape.add(
            scene,
            meshes,
            base,
            rng.range(0.0, std::f32::consts::TAU),
            material,
        );
        let center = Vec2::new(base.x, base.z);
        obstacles.push(Obstacle {
            center,
            radius,
            bottom: base.y,
            top: base.y + height,
        });
        if let Shape::Cuboid { half } = shape {
            shelves.push(Shelf {
                center,
                height: base.y + height,
                radius: half.x.min(half.z),
            });
        }
    }
}

/// Where an object of footprint `radius` and `height` can stand: sometimes
/// on a free shelf (which is then taken), otherwise on the floor, clear of
/// the walls and of `obstacles`; `None` if no spot is found.
fn place(
    rng: &mut Rng,
    room: &Room,
    obstacles: &[Obstacle],
    shelves: &mut Vec<Shelf>,
    radius: f32,
    height: f32,
) -> Option<Vec3> {
    let fits = |c: Vec2, bottom: f32| {
        let me = Obstacle {
            center: c,
            radius,
            bottom,
            top: bottom + height,
        };
        me.top < room.height - 0.3 && !obstacles.iter().any(|o| o.overlaps(&me, 0.05))
    };
    if rng.chance(0.3) {
        let free: Vec<usize> = (0..shelves.len())
            .filter(|&i| shelves[i].radius >= radius && fits(shelves[i].center, shelves[i].height))
            .collect();
        if !free.is_empty() {
            let shelf = shelves.swap_remove(free[rng.index(free.len())]);
            return Some(Vec3::new(shelf.center.x, shelf.height, shelf.center.y));
        }
    }
    let reach = room.half - Vec2::splat(radius + 0.1);
    (0..40).find_map(|_| {
        let c = Vec2::new(rng.range(-reach.x, reach.x), rng.range(-reach.y, reach.y));
        fits(c, 0.0).then_some(Vec3::new(c.x, 0.0, c.y))
    })
}
