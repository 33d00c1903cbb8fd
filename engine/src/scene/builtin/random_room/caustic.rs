//! Now and then a caustic: a smooth glass sphere on the floor under a small, bright panel light
//! that hangs above and beside it, so that the sphere focuses the light into a caustic on the
//! floor, as in the held-out `caustics` scene but inside a room. At one sample per pixel a caustic
//! arrives as rare, very bright samples, which a denoiser must neither drop as fireflies nor
//! smear: training data without caustics teaches it to drop them.

use glam::{Vec2, Vec3};

use super::materials::light_tint;
use super::placement::Obstacle;
use super::rng::Rng;
use super::room::Room;
use crate::scene::builtin::shapes::MeshBuilder;
use crate::scene::{Material, Scene};

/// The share of the rooms that get a caustic.
const CHANCE: f32 = 0.4;
/// The glass sphere's radius, metres.
const SPHERE_RADIUS: (f32, f32) = (0.2, 0.45);
/// The lamp's side, metres: small, so that the caustic is sharp.
const LAMP_SIDE: (f32, f32) = (0.05, 0.15);
/// The lamp's height over the sphere's top, metres.
const LAMP_HEIGHT: (f32, f32) = (0.6, 1.8);
/// The lamp's distance beside the sphere's centre, in sphere radii: the caustic falls on the far
/// side.
const LAMP_OFFSET: (f32, f32) = (0.3, 1.2);
/// The lamp's power (π times radiance times area, as for the room's lights).
const LAMP_POWER: (f32, f32) = (8.0, 40.0);
/// Gap kept between the sphere, the lamp and everything already in the room, metres.
const GAP: f32 = 0.1;
/// The name of the sphere's material.
pub const GLASS: &str = "caustic-glass";
/// The name of the lamp's material.
pub const LAMP: &str = "caustic-lamp";

/// With probability [`CHANCE`], adds a glass sphere and its lamp where they fit clear of the
/// walls, the ceiling and `obstacles` (to which both are then added); a room with no room for them
/// gets none.
pub fn add(scene: &mut Scene, rng: &mut Rng, room: &Room, obstacles: &mut Vec<Obstacle>) {
    if !rng.chance(CHANCE) {
        return;
    }
    let radius = rng.range(SPHERE_RADIUS.0, SPHERE_RADIUS.1);
    let side = rng.range(LAMP_SIDE.0, LAMP_SIDE.1);
    let lift = rng.range(LAMP_HEIGHT.0, LAMP_HEIGHT.1);
    let offset = rng.range(LAMP_OFFSET.0, LAMP_OFFSET.1) * radius;
    let power = rng.range(LAMP_POWER.0, LAMP_POWER.1);
    let tint = light_tint(rng);
    let lamp_y = (2.0 * radius + lift).min(room.height - 0.3);
    if lamp_y < 2.0 * radius + 0.3 {
        return;
    }
    let reach = room.half - Vec2::splat(radius + offset + side + GAP);
    if reach.min_element() <= 0.0 {
        return;
    }
    let spot = (0..40).find_map(|_| {
        let center = Vec2::new(rng.range(-reach.x, reach.x), rng.range(-reach.y, reach.y));
        let angle = rng.range(0.0, std::f32::consts::TAU);
        let lamp = center + offset * Vec2::new(angle.cos(), angle.sin());
        let sphere = Obstacle {
            center,
            radius,
            bottom: 0.0,
            top: 2.0 * radius,
        };
        // The column from the floor up to the lamp, so that nothing stands in the light's way.
        let column = Obstacle {
            center: 0.5 * (center + lamp),
            radius: 0.5 * offset + radius.max(side),
            bottom: 0.0,
            top: lamp_y + 0.05,
        };
        let clear = !obstacles.iter().any(|o| o.overlaps(&column, GAP));
        clear.then_some((sphere, lamp))
    });
    let Some((sphere, lamp)) = spot else {
        return;
    };
    let glass = scene.add_material(Material::dielectric(GLASS, 1.5, 0.0));
    scene.add_sphere(
        Vec3::new(sphere.center.x, radius, sphere.center.y),
        radius,
        glass,
    );
    let radiance = power / (std::f32::consts::PI * side * side);
    let material = scene.add_material(Material::emissive(LAMP, tint * radiance));
    let mut panel = MeshBuilder::new();
    panel.quad(
        Vec3::new(lamp.x - 0.5 * side, lamp_y, lamp.y - 0.5 * side),
        Vec3::X * side,
        Vec3::Z * side,
        1,
        1,
    );
    scene.add_mesh_instance(panel.build(LAMP, material));
    obstacles.push(sphere);
    obstacles.push(Obstacle {
        center: lamp,
        radius: side,
        bottom: lamp_y - 0.05,
        top: lamp_y + 0.05,
    });
}
