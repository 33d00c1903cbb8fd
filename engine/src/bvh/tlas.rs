//! The top-level acceleration structure over instances.

use super::build::{self, PrimRef};
use super::{Aabb, BvhNode};

/// A top-level BVH over instance world bounds.
#[derive(Clone, Debug)]
pub struct Tlas {
    /// Flattened nodes, root first; leaves index into [`Tlas::order`].
    pub nodes: Vec<BvhNode>,
    /// Leaf order: `order[i]` is the index into `Bvh::instances` of the
    /// i-th leaf entry.
    pub order: Vec<u32>,
}

impl Tlas {
    /// Builds over the given world-space instance bounds.
    pub fn build(bounds: &[Aabb]) -> Self {
        let prims = bounds
            .iter()
            .enumerate()
            .filter(|(_, b)| !b.is_empty())
            .map(|(i, b)| PrimRef::new(b, i as u32))
            .collect();
        let tree = build::build(prims);
        Self {
            nodes: tree.nodes,
            order: tree.order,
        }
    }

    /// SAH cost of the top level alone.
    pub fn sah_cost(&self) -> f32 {
        build::sah_cost(&self.nodes)
    }
}
