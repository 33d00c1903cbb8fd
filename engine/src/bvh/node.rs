//! The flattened node layout shared by the CPU traversal and the GPU.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use super::Aabb;

/// One node of a flattened binary BVH: 32 bytes, two per cache line.
///
/// std430 layout (GLSL mirror, all members 4-byte aligned, stride 32):
/// ```glsl
/// struct BvhNode {
///     float min_x, min_y, min_z;
///     uint  left_or_first; // interior: index of the left child (right = left + 1)
///                          // leaf: index of the first primitive
///     float max_x, max_y, max_z;
///     uint  count;         // 0 = interior node, otherwise primitives in the leaf
/// };
/// ```
/// Children of an interior node are always stored next to each other, so
/// a single index suffices. The root of every tree is its first node. An
/// empty tree is a single node with `count == 0` and `left_or_first == 0`;
/// since no real child is ever node 0, traversals skip such a node.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BvhNode {
    /// Smallest corner of the node bounds.
    pub min: [f32; 3],
    /// Left child index (interior) or first primitive (leaf).
    pub left_or_first: u32,
    /// Largest corner of the node bounds.
    pub max: [f32; 3],
    /// Primitive count; zero marks an interior node.
    pub count: u32,
}

impl BvhNode {
    /// A leaf over `count` primitives starting at `first`.
    pub fn leaf(bounds: &Aabb, first: u32, count: u32) -> Self {
        Self {
            min: bounds.min.to_array(),
            left_or_first: first,
            max: bounds.max.to_array(),
            count,
        }
    }

    /// An interior node whose children are `left` and `left + 1`.
    pub fn interior(bounds: &Aabb, left: u32) -> Self {
        Self {
            min: bounds.min.to_array(),
            left_or_first: left,
            max: bounds.max.to_array(),
            count: 0,
        }
    }

    /// Whether this node is a leaf.
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }

    /// The node bounds.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(Vec3::from(self.min), Vec3::from(self.max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_is_32_bytes() {
        assert_eq!(std::mem::size_of::<BvhNode>(), 32);
        let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
        assert!(BvhNode::leaf(&b, 3, 2).is_leaf());
        assert!(!BvhNode::interior(&b, 1).is_leaf());
    }
}
