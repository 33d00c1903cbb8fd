//! Bottom-level acceleration structures: one per mesh, plus one over all
//! analytic spheres.

use glam::{UVec3, Vec3};
use rayon::prelude::*;

use super::build::{self, PrimRef};
use super::{Aabb, BvhNode, Sphere};

/// The geometry a [`Blas`] was built over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlasGeometry {
    /// Triangles of `Scene::meshes[index]`.
    Mesh(u32),
    /// All of `Scene::spheres`.
    Spheres,
}

/// A bottom-level BVH in object space.
#[derive(Clone, Debug)]
pub struct Blas {
    /// Flattened nodes, root first; leaves index into [`Blas::order`].
    pub nodes: Vec<BvhNode>,
    /// Leaf order: `order[i]` is the source primitive (triangle or sphere)
    /// index of the i-th leaf primitive.
    pub order: Vec<u32>,
    /// What the leaves reference.
    pub geometry: BlasGeometry,
}

impl Blas {
    /// Builds over the triangles of mesh `mesh` (positions and index
    /// triples given in object space).
    pub fn triangles(mesh: u32, positions: &[Vec3], indices: &[UVec3]) -> Self {
        let prims: Vec<PrimRef> = indices
            .par_iter()
            .enumerate()
            .map(|(i, t)| {
                let b = Aabb::from_points([
                    positions[t.x as usize],
                    positions[t.y as usize],
                    positions[t.z as usize],
                ]);
                PrimRef::new(&b, i as u32)
            })
            .collect();
        let tree = build::build(prims);
        Self {
            nodes: tree.nodes,
            order: tree.order,
            geometry: BlasGeometry::Mesh(mesh),
        }
    }

    /// Builds over analytic spheres (world space).
    pub fn spheres(spheres: &[Sphere]) -> Self {
        let prims = spheres
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let r = Vec3::splat(s.radius);
                PrimRef::new(&Aabb::new(s.center - r, s.center + r), i as u32)
            })
            .collect();
        let tree = build::build(prims);
        Self {
            nodes: tree.nodes,
            order: tree.order,
            geometry: BlasGeometry::Spheres,
        }
    }

    /// Object-space bounds of the whole tree.
    pub fn bounds(&self) -> Aabb {
        if self.order.is_empty() {
            Aabb::EMPTY
        } else {
            self.nodes[0].bounds()
        }
    }

    /// SAH cost of the tree (see `scene::Bvh::sah_cost`).
    pub fn sah_cost(&self) -> f32 {
        build::sah_cost(&self.nodes)
    }
}
