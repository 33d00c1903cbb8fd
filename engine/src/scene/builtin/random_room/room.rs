//! The room's shell: floor (plain or tiled in two albedos, matte, polished or metal), four walls
//! (some in an accent colour, some with a wainscot band) and a ceiling.
//! Sometimes the back wall (`z = -depth/2`) has windows, and then a sun
//! and sky (as in `blinds-room`) shine in through them.

use glam::{Vec2, Vec3};

use super::materials::muted;
use super::rng::Rng;
use crate::scene::builtin::shapes::{wall_with_openings, MeshBuilder};
use crate::scene::{Environment, Material, Scene, Sun};

/// An axis-aligned room with its floor at `y = 0`, centred on the origin.
#[derive(Clone, Copy, Debug)]
pub struct Room {
    /// Half the width (`x`) and half the depth (`z`).
    pub half: Vec2,
    /// Ceiling height.
    pub height: f32,
}

impl Room {
    /// A room 3 to 10 m wide and deep and 2.5 to 4.5 m high.
    pub fn random(rng: &mut Rng) -> Self {
        Self {
            half: Vec2::new(rng.range(1.5, 5.0), rng.range(1.5, 5.0)),
            height: rng.range(2.5, 4.5),
        }
    }

    /// Area of floor, ceiling and walls.
    pub fn surface_area(&self) -> f32 {
        let (a, b) = (self.half.x, self.half.y);
        8.0 * a * b + 4.0 * self.height * (a + b)
    }

    /// Whether `p` lies inside the room shrunk by `margin` on every side.
    pub fn contains(&self, p: Vec3, margin: f32) -> bool {
        let (lo, hi) = self.inner(margin);
        p.cmpge(lo).all() && p.cmple(hi).all()
    }

    /// The nearest point to `p` inside the room shrunk by `margin`.
    pub fn clamp(&self, p: Vec3, margin: f32) -> Vec3 {
        let (lo, hi) = self.inner(margin);
        p.clamp(lo, hi)
    }

    fn inner(&self, margin: f32) -> (Vec3, Vec3) {
        let (a, b) = (self.half.x, self.half.y);
        (
            Vec3::new(-a, 0.0, -b) + margin,
            Vec3::new(a, self.height, b) - margin,
        )
    }
}

/// A pale, slightly tinted wall or ceiling albedo.
fn pale(rng: &mut Rng) -> Vec3 {
    muted(rng, 0.35, 0.85, 0.12)
}

/// Adds the shell of `room`; returns whether it has windows. The floor's finish is drawn from
/// `finish`, a stream of its own, so that it leaves the rest of the room as it was.
pub fn add(scene: &mut Scene, rng: &mut Rng, finish: &mut Rng, room: &Room) -> bool {
    let (a, b, h) = (room.half.x, room.half.y, room.height);
    let wall = scene.add_material(Material::diffuse("wall", pale(rng)));
    let wainscot = if rng.chance(0.4) {
        let band = Material::diffuse("wainscot", muted(rng, 0.08, 0.7, 0.5));
        Some((scene.add_material(band), rng.range(0.6, 1.2) / h))
    } else {
        None
    };
    let windows = rng.chance(0.4);
    let walls = [
        (Vec3::new(-a, 0.0, -b), Vec3::X * 2.0 * a),
        (Vec3::new(a, 0.0, b), Vec3::NEG_X * 2.0 * a),
        (Vec3::new(-a, 0.0, b), Vec3::NEG_Z * 2.0 * b),
        (Vec3::new(a, 0.0, -b), Vec3::Z * 2.0 * b),
    ];
    let up = Vec3::Y * h;
    for (k, (corner, along)) in walls.into_iter().enumerate() {
        let material = if rng.chance(0.2) {
            let accent = Material::diffuse(&format!("accent-wall-{k}"), muted(rng, 0.1, 0.7, 0.7));
            scene.add_material(accent)
        } else {
            wall
        };
        let mut mesh = MeshBuilder::new();
        if k == 0 && windows {
            wall_with_openings(&mut mesh, corner, along, up, &window_openings(rng, room));
        } else if let Some((band, f)) = wainscot {
            mesh.quad(corner + up * f, along, up * (1.0 - f), 1, 1);
            let mut lower = MeshBuilder::new();
            lower.quad(corner, along, up * f, 1, 1);
            scene.add_mesh_instance(lower.build(&format!("wainscot-{k}"), band));
        } else {
            mesh.quad(corner, along, up, 1, 1);
        }
        scene.add_mesh_instance(mesh.build(&format!("wall-{k}"), material));
    }
    add_floor(scene, rng, finish, room);
    let ceiling = scene.add_material(Material::diffuse("ceiling", pale(rng)));
    let mut mesh = MeshBuilder::new();
    mesh.quad(
        Vec3::new(-a, h, -b),
        Vec3::X * 2.0 * a,
        Vec3::Z * 2.0 * b,
        1,
        1,
    );
    scene.add_mesh_instance(mesh.build("ceiling", ceiling));
    if windows {
        add_sun_and_sky(scene, rng);
    }
    windows
}

/// A plain floor, or half the time a checkerboard of two albedos, in the finish `finish` draws.
fn add_floor(scene: &mut Scene, rng: &mut Rng, finish: &mut Rng, room: &Room) {
    let (a, b) = (room.half.x, room.half.y);
    let finish = FloorFinish::random(finish);
    let base = scene.add_material(finish.material("floor", muted(rng, 0.05, 0.6, 0.4)));
    if !rng.chance(0.5) {
        let mut mesh = MeshBuilder::new();
        mesh.quad(
            Vec3::new(-a, 0.0, b),
            Vec3::X * 2.0 * a,
            Vec3::NEG_Z * 2.0 * b,
            1,
            1,
        );
        scene.add_mesh_instance(mesh.build("floor", base));
        return;
    }
    let other = scene.add_material(finish.material("floor-tile", muted(rng, 0.05, 0.8, 0.4)));
    let tile = rng.range(0.4, 1.0);
    let (nx, nz) = (
        (2.0 * a / tile).round().max(1.0) as u32,
        (2.0 * b / tile).round().max(1.0) as u32,
    );
    let (tx, tz) = (2.0 * a / nx as f32, 2.0 * b / nz as f32);
    let mut tiles = [MeshBuilder::new(), MeshBuilder::new()];
    for i in 0..nx {
        for j in 0..nz {
            let corner = Vec3::new(-a + i as f32 * tx, 0.0, -b + (j + 1) as f32 * tz);
            tiles[((i + j) % 2) as usize].quad(corner, Vec3::X * tx, Vec3::NEG_Z * tz, 1, 1);
        }
    }
    let [even, odd] = tiles;
    scene.add_mesh_instance(even.build("floor", base));
    scene.add_mesh_instance(odd.build("floor-tiles", other));
}

/// How a floor reflects: mostly matte, sometimes polished (a specular layer over its colour, as
/// stone or varnished wood) or bare metal, both glossy enough to mirror the room blurrily, the case
/// where reprojected history smears reflections.
#[derive(Clone, Copy)]
enum FloorFinish {
    Matte,
    Polished { alpha: f32 },
    Metal { alpha: f32 },
}

impl FloorFinish {
    /// Matte 65 %, polished (GGX alpha 0.02 to 0.2) 25 %, metal (alpha 0.03 to 0.25) 10 %.
    fn random(rng: &mut Rng) -> Self {
        match rng.weighted(&[0.65, 0.25, 0.1]) {
            0 => Self::Matte,
            1 => Self::Polished {
                alpha: rng.range(0.02, 0.2),
            },
            _ => Self::Metal {
                alpha: rng.range(0.03, 0.25),
            },
        }
    }

    /// A floor material of colour `color` in this finish (a metal's colour lightened to a
    /// plausible reflectance).
    fn material(self, name: &str, color: Vec3) -> Material {
        match self {
            Self::Matte => Material::diffuse(name, color),
            Self::Polished { alpha } => Material::metal_rough(name, color, 0.0, alpha),
            Self::Metal { alpha } => Material::conductor(name, 0.5 + 0.5 * color, alpha),
        }
    }
}

/// One to three windows side by side in the back wall, as
/// `(u0, v0, u1, v1)` fractions of its width and height.
fn window_openings(rng: &mut Rng, room: &Room) -> Vec<[f32; 4]> {
    let h = room.height;
    let count = rng.int(1, ((2.0 * room.half.x / 1.5) as u32).clamp(1, 3));
    let slot = 1.0 / count as f32;
    let sill = rng.range(0.5, 1.0) / h;
    let top = (h - rng.range(0.3, 0.6)) / h;
    (0..count)
        .map(|k| {
            let width = slot * rng.range(0.4, 0.8);
            let u0 = k as f32 * slot + rng.range(0.0, slot - width);
            [u0, sill, u0 + width, top]
        })
        .collect()
}

/// A sun behind the back wall, high enough to shine in through its
/// windows, and a sky of random brightness.
fn add_sun_and_sky(scene: &mut Scene, rng: &mut Rng) {
    scene.sun = Some(Sun {
        direction: Vec3::new(rng.range(-0.7, 0.7), rng.range(0.35, 1.0), -1.0).normalize(),
        irradiance: Vec3::new(6.0, 5.6, 5.0) * rng.range(0.5, 1.5),
        angular_radius: 0.00465,
    });
    let k = rng.range(0.5, 1.5);
    scene.environment = Environment::Sky {
        zenith: Vec3::new(0.25, 0.4, 0.8) * k,
        horizon: Vec3::new(0.7, 0.8, 0.95) * k,
        ground: Vec3::new(0.2, 0.18, 0.15) * k,
    };
}
