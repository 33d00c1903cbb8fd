//! The BVH layout the GPU walks: every interior node holds the boxes of both its children and how
//! to reach each (a *child word*: another interior node, or a leaf's primitive range), so one 64-byte
//! load per step gives both boxes and no load is spent on finding out that a child is a leaf.
//! Packed from the flattened binary trees of [`crate::bvh`], which the CPU traversal keeps using.

use bytemuck::{Pod, Zeroable};

use crate::bvh::BvhNode;

/// Set in a child word that names a leaf.
pub const LEAF: u32 = 1 << 31;
/// Bits of a leaf word holding its first primitive (below the count bits).
pub const LEAF_FIRST_BITS: u32 = 27;
/// Most primitives one leaf word can name (larger leaves are split when packing).
pub const MAX_LEAF_PRIMITIVES: u32 = 16;
/// Most primitives a packed tree can index (leaf words hold 27 bits of primitive index).
pub const MAX_PRIMITIVES: u32 = 1 << LEAF_FIRST_BITS;
/// The root word of an empty tree.
pub const EMPTY: u32 = u32::MAX;

/// An interior node as the GPU walks it, 64 bytes (std430):
/// ```glsl
/// struct BvhNode {
///     vec3 left_min;  uint left;   // child words (see bvh_pack::LEAF)
///     vec3 left_max;  uint right;
///     vec3 right_min; uint pad0;
///     vec3 right_max; uint pad1;
/// };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuBvhNode {
    /// Smallest corner of the left child's box.
    pub left_min: [f32; 3],
    /// The left child's word.
    pub left: u32,
    /// Largest corner of the left child's box.
    pub left_max: [f32; 3],
    /// The right child's word.
    pub right: u32,
    /// Smallest corner of the right child's box.
    pub right_min: [f32; 3],
    /// Padding.
    pub pad0: u32,
    /// Largest corner of the right child's box.
    pub right_max: [f32; 3],
    /// Padding.
    pub pad1: u32,
}

/// What a child word names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Child {
    /// An interior node (index in the packed node array).
    Node(u32),
    /// `count` primitives from `first`.
    Leaf {
        /// First primitive.
        first: u32,
        /// Number of primitives (1 to [`MAX_LEAF_PRIMITIVES`]).
        count: u32,
    },
}

impl Child {
    /// Decodes a child word (not [`EMPTY`]).
    pub fn from_word(word: u32) -> Self {
        if word & LEAF == 0 {
            return Child::Node(word);
        }
        Child::Leaf {
            first: word & (MAX_PRIMITIVES - 1),
            count: ((word >> LEAF_FIRST_BITS) & (MAX_LEAF_PRIMITIVES - 1)) + 1,
        }
    }
}

fn leaf_word(first: u32, count: u32) -> u32 {
    LEAF | ((count - 1) << LEAF_FIRST_BITS) | first
}

/// Appends the tree `nodes` (flattened binary, root first, as built by [`crate::bvh`]) to `out`,
/// adding `prim_base` to its primitive indices; returns the root's child word ([`EMPTY`] for an
/// empty tree). Leaves over more than [`MAX_LEAF_PRIMITIVES`] primitives are split under interior
/// nodes with the leaf's box.
///
/// # Panics
/// If a primitive index reaches [`MAX_PRIMITIVES`] (scenes are validated against it).
pub fn pack_tree(nodes: &[BvhNode], prim_base: u32, out: &mut Vec<GpuBvhNode>) -> u32 {
    match nodes.first() {
        None => EMPTY,
        Some(root) if !root.is_leaf() && root.left_or_first == 0 => EMPTY,
        Some(_) => Packer {
            nodes,
            prim_base,
            out,
        }
        .word(0),
    }
}

/// Packs one tree; interior nodes are laid out depth first, left child right after its parent.
struct Packer<'a> {
    nodes: &'a [BvhNode],
    prim_base: u32,
    out: &'a mut Vec<GpuBvhNode>,
}

impl Packer<'_> {
    /// The word of binary node `index`, packing its subtree.
    fn word(&mut self, index: usize) -> u32 {
        let node = self.nodes[index];
        if node.is_leaf() {
            return self.leaf(&node, self.prim_base + node.left_or_first, node.count);
        }
        let left = node.left_or_first as usize;
        let slot = self.reserve();
        let left_word = self.word(left);
        let right_word = self.word(left + 1);
        self.out[slot] = interior(
            (&self.nodes[left], left_word),
            (&self.nodes[left + 1], right_word),
        );
        slot as u32
    }

    /// The word of a leaf over `count` primitives from `first` with `node`'s box, split in halves
    /// under interior nodes while it is too large for one word.
    fn leaf(&mut self, node: &BvhNode, first: u32, count: u32) -> u32 {
        assert!(
            first + count <= MAX_PRIMITIVES,
            "BVH primitive index {} beyond the GPU layout's limit {MAX_PRIMITIVES}",
            first + count
        );
        if count <= MAX_LEAF_PRIMITIVES {
            return leaf_word(first, count);
        }
        let half = count / 2;
        let slot = self.reserve();
        let left_word = self.leaf(node, first, half);
        let right_word = self.leaf(node, first + half, count - half);
        self.out[slot] = interior((node, left_word), (node, right_word));
        slot as u32
    }

    fn reserve(&mut self) -> usize {
        self.out.push(GpuBvhNode::default());
        self.out.len() - 1
    }
}

fn interior(
    (left, left_word): (&BvhNode, u32),
    (right, right_word): (&BvhNode, u32),
) -> GpuBvhNode {
    GpuBvhNode {
        left_min: left.min,
        left: left_word,
        left_max: left.max,
        right: right_word,
        right_min: right.min,
        pad0: 0,
        right_max: right.max,
        pad1: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::Aabb;
    use glam::Vec3;

    fn unit() -> Aabb {
        Aabb::new(Vec3::ZERO, Vec3::ONE)
    }

    #[test]
    fn a_single_leaf_is_a_leaf_word_and_empty_trees_are_empty() {
        let mut out = Vec::new();
        assert_eq!(
            Child::from_word(pack_tree(&[BvhNode::leaf(&unit(), 3, 2)], 10, &mut out)),
            Child::Leaf {
                first: 13,
                count: 2
            }
        );
        assert!(out.is_empty());
        let empty = BvhNode::leaf(&Aabb::new(Vec3::ZERO, Vec3::ZERO), 0, 0);
        assert_eq!(pack_tree(&[empty], 0, &mut out), EMPTY);
        assert_eq!(pack_tree(&[], 0, &mut out), EMPTY);
    }

    #[test]
    fn interior_nodes_carry_their_children_boxes_and_words() {
        let left = Aabb::new(Vec3::ZERO, Vec3::splat(0.5));
        let right = Aabb::new(Vec3::splat(0.5), Vec3::ONE);
        let nodes = [
            BvhNode::interior(&unit(), 1),
            BvhNode::leaf(&left, 0, 4),
            BvhNode::leaf(&right, 4, 1),
        ];
        let mut out = vec![GpuBvhNode::default()];
        let root = pack_tree(&nodes, 0, &mut out);
        assert_eq!(Child::from_word(root), Child::Node(1));
        let n = out[1];
        assert_eq!((n.left_min, n.left_max), (left.min.into(), left.max.into()));
        assert_eq!(
            (n.right_min, n.right_max),
            (right.min.into(), right.max.into())
        );
        assert_eq!(Child::from_word(n.left), Child::Leaf { first: 0, count: 4 });
        assert_eq!(
            Child::from_word(n.right),
            Child::Leaf { first: 4, count: 1 }
        );
    }

    #[test]
    fn oversized_leaves_are_split_and_keep_every_primitive() {
        let mut out = Vec::new();
        let root = pack_tree(&[BvhNode::leaf(&unit(), 0, 37)], 5, &mut out);
        let mut covered = Vec::new();
        let mut stack = vec![root];
        while let Some(word) = stack.pop() {
            match Child::from_word(word) {
                Child::Leaf { first, count } => covered.extend(first..first + count),
                Child::Node(i) => {
                    let n = out[i as usize];
                    assert_eq!((n.left_min, n.right_max), ([0.0; 3], [1.0; 3]));
                    stack.extend([n.left, n.right]);
                }
            }
        }
        covered.sort_unstable();
        assert_eq!(covered, (5..42).collect::<Vec<_>>());
    }
}
