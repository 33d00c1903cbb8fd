//! What occupies the room (for placing objects and steering the camera
//! clear of them), and the meshes that objects and lights share.

use glam::{Vec2, Vec3};

use crate::scene::builtin::shapes::{self, MeshBuilder};
use crate::scene::builtin::teapot;
use crate::scene::Scene;

/// A vertical cylinder bounding something in the room.
#[derive(Clone, Copy, Debug)]
pub struct Obstacle {
    /// Centre on the floor plane (`x`, `z`).
    pub center: Vec2,
    /// Radius of the footprint.
    pub radius: f32,
    /// Lowest height.
    pub bottom: f32,
    /// Highest height.
    pub top: f32,
}

impl Obstacle {
    /// The middle of the bounding cylinder, where the camera looks.
    pub fn focus(&self) -> Vec3 {
        Vec3::new(self.center.x, 0.5 * (self.bottom + self.top), self.center.y)
    }

    /// Whether the two cylinders, footprints widened by `gap`, intersect.
    pub fn overlaps(&self, other: &Obstacle, gap: f32) -> bool {
        self.center.distance(other.center) < self.radius + other.radius + gap
            && self.bottom < other.top
            && other.bottom < self.top
    }

    /// Whether `p` is within `clearance` of the cylinder.
    pub fn blocks(&self, p: Vec3, clearance: f32) -> bool {
        Vec2::new(p.x, p.z).distance(self.center) < self.radius + clearance
            && p.y > self.bottom - clearance
            && p.y < self.top + clearance
    }
}

/// Unit meshes added to the scene on first use and instanced with a
/// material override ever after.
#[derive(Default)]
pub struct SharedMeshes {
    cube: Option<u32>,
    cylinder: Option<u32>,
    teapot: Option<u32>,
}

/// Tessellation of the teapot: 8 x 8 quads per patch, about 4 k triangles.
const TEAPOT_DIVS: u32 = 8;

impl SharedMeshes {
    /// The `[-1, 1]³` cube.
    pub fn cube(&mut self, scene: &mut Scene, material: u32) -> u32 {
        *self
            .cube
            .get_or_insert_with(|| scene.add_mesh(shapes::cube("cube", material)))
    }

    /// A closed cylinder of radius 1 along `+Y` from `y = 0` to `y = 1`.
    pub fn cylinder(&mut self, scene: &mut Scene, material: u32) -> u32 {
        *self.cylinder.get_or_insert_with(|| {
            let mut b = MeshBuilder::new();
            b.cylinder(Vec3::ZERO, 1.0, 1.0, 32, 1);
            scene.add_mesh(b.build("cylinder", material))
        })
    }

    /// The Utah teapot, 3.15 high, standing on `y = 0`.
    pub fn teapot(&mut self, scene: &mut Scene, material: u32) -> u32 {
        *self
            .teapot
            .get_or_insert_with(|| scene.add_mesh(teapot("teapot", material, TEAPOT_DIVS)))
    }
}
