//! Bounding volume hierarchies for ray tracing: the trees, their builder,
//! rays and primitive intersection. The scene's two-level BVH over these
//! (`scene::Bvh`) lives with the scene it is built from.
//!
//! # Layout
//!
//! Two levels. Every mesh gets a bottom-level BVH ([`Blas`]) in object
//! space, all analytic spheres share one more BLAS, and a top-level BVH
//! ([`Tlas`]) is built over the world bounds of the instances. Moving an
//! instance only requires `scene::Bvh::rebuild_top_level`.
//!
//! Every tree is a compact binary BVH of 32-byte [`BvhNode`]s built with a
//! multi-threaded binned SAH builder ([`build`]). Children of an interior
//! node are adjacent, leaves hold up to 8 primitives as a contiguous range
//! of the tree's primitive order. For the GPU, these trees are packed in
//! one of two layouts (binary, or collapsed into compressed 8-wide nodes)
//! and triangles are reordered in the packed tree's order (see
//! `scene::gpu`), so leaves index the triangle list directly and no
//! indirection array is needed.
//!
//! The CPU traversal (`scene::Bvh::intersect`, `scene::Bvh::occluded`) handles
//! triangles and spheres through instance transforms; it serves tests and
//! picking.

mod aabb;
mod blas;
pub mod build;
mod intersect;
mod node;
mod ray;
mod sphere;
mod tlas;
mod traverse;

pub use aabb::Aabb;
pub use blas::{Blas, BlasGeometry};
pub use intersect::{ray_sphere, ray_triangle};
pub use node::BvhNode;
pub use ray::{Hit, HitKind, Ray};
pub use sphere::Sphere;
pub use tlas::Tlas;
pub(crate) use traverse::walk;
