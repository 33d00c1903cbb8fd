//! The compressed wide BVH the GPU can walk instead of the binary one (after Ylitie, Karras and
//! Laine 2017, "Efficient incoherent ray traversal on GPUs through compressed wide BVHs"): 8-wide
//! 80-byte nodes ([`WideNode`]) whose children's boxes are quantized to bytes against a per-node
//! origin and power-of-two scales, with a meta byte per child. Built from the flattened binary SAH
//! trees of [`crate::bvh`] by a greedy largest-surface-area collapse ([`collapse`]); the children
//! take slots by octant ([`slots`]) so that a ray visits them near to far. The primitives are
//! reordered so that each node's leaf children name contiguous primitives from one base index.
//! [`walk`] traverses the packed nodes on the CPU exactly as `shaders/common/traverse.glsl` does.

pub mod collapse;
mod node;
pub mod slots;
mod walk;

pub use node::{Slot, WideNode, INNER_BIT, MAX_LEAF_PRIMITIVES, MAX_NODE_PRIMITIVES, WIDTH};
pub use walk::walk;

use crate::bvh::BvhNode;
use collapse::{Child, Collapser};

/// The root index of an empty tree.
pub const EMPTY: u32 = u32::MAX;

/// A binary tree packed as wide nodes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PackedWide {
    /// Index of the root node ([`EMPTY`] for an empty tree).
    pub root: u32,
    /// The primitive order the nodes index: `order[k]` is the binary tree's leaf-order position of
    /// packed primitive `prim_base + k`.
    pub order: Vec<u32>,
    /// Nodes on the longest root-to-leaf path (0 for an empty tree); the GPU traversal stacks at
    /// most one entry per level below the root.
    pub depth: u32,
}

/// Appends the wide form of the flattened binary tree `nodes` (root first, as built by
/// [`crate::bvh`]) to `out`; its leaves name primitives from `prim_base`. Each node's inner
/// children are stored contiguously; subtrees are laid out depth first.
pub fn pack_tree(nodes: &[BvhNode], prim_base: u32, out: &mut Vec<WideNode>) -> PackedWide {
    match nodes.first() {
        None => return empty(),
        Some(root) if !root.is_leaf() && root.left_or_first == 0 => return empty(),
        Some(_) => {}
    }
    let collapser = Collapser::new(nodes);
    let root = out.len() as u32;
    out.push(WideNode::default());
    let mut order = Vec::new();
    let mut depth = 0;
    // (wide node slot, binary node, depth)
    let mut stack = vec![(root, 0u32, 1u32)];
    while let Some((at, binary, level)) = stack.pop() {
        depth = depth.max(level);
        let children = collapser.children(binary);
        let centers: Vec<_> = children.iter().map(|c| c.bounds().center()).collect();
        let center = children
            .iter()
            .fold(crate::bvh::Aabb::EMPTY, |b, c| b.union(c.bounds()))
            .center();
        let placement = slots::assign(&centers, center);
        let child_base = out.len() as u32;
        let primitive_base = prim_base + order.len() as u32;
        let mut slot_contents = [Slot::Empty; WIDTH];
        let mut inner = Vec::new();
        for (s, child) in placement.iter().enumerate() {
            let Some(k) = *child else { continue };
            slot_contents[s] = match children[k] {
                Child::Inner { index, bounds } => {
                    inner.push(index);
                    Slot::Inner(bounds)
                }
                Child::Leaf {
                    first,
                    count,
                    bounds,
                } => {
                    let offset = prim_base + order.len() as u32 - primitive_base;
                    order.extend(first..first + count);
                    Slot::Leaf {
                        bounds,
                        offset,
                        count,
                    }
                }
            };
        }
        out[at as usize] = WideNode::new(&slot_contents, child_base, primitive_base);
        out.resize(out.len() + inner.len(), WideNode::default());
        for (r, &index) in inner.iter().enumerate().rev() {
            stack.push((child_base + r as u32, index, level + 1));
        }
    }
    PackedWide { root, order, depth }
}

fn empty() -> PackedWide {
    PackedWide {
        root: EMPTY,
        order: Vec::new(),
        depth: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::build::{build, PrimRef};
    use crate::bvh::Aabb;
    use glam::Vec3;

    fn prims(n: u32) -> Vec<PrimRef> {
        (0..n)
            .map(|i| {
                let p = Vec3::new((i % 23) as f32, (i / 23 % 19) as f32, (i * 3 % 7) as f32);
                PrimRef::new(&Aabb::new(p, p + Vec3::new(0.7, 0.3, 0.5)), i)
            })
            .collect()
    }

    /// Every packed primitive lies in the dequantized box of the leaf naming it; every primitive
    /// is named once.
    #[test]
    fn packed_boxes_contain_their_primitives() {
        for n in [1, 2, 5, 9, 2000] {
            let p = prims(n);
            let tree = build(p.clone());
            let mut out = vec![WideNode::default(); 3];
            let packed = pack_tree(&tree.nodes, 10, &mut out);
            assert_eq!(packed.root, 3);
            assert_eq!(packed.order.len(), n as usize);
            let mut seen = vec![0; n as usize];
            let mut stack = vec![packed.root];
            while let Some(i) = stack.pop() {
                let node = out[i as usize];
                let mut rank = 0;
                for s in 0..WIDTH {
                    let b = node.child_bounds(s);
                    let meta = node.meta[s];
                    if meta == 0 {
                        continue;
                    }
                    if node.inner_mask & (1 << s) != 0 {
                        stack.push(node.child_base + rank);
                        rank += 1;
                        continue;
                    }
                    let count = (u32::from(meta) >> 5).count_ones();
                    let first = node.primitive_base + u32::from(meta & 31) - 10;
                    for k in first..first + count {
                        let source = tree.order[packed.order[k as usize] as usize];
                        let q = &p[source as usize];
                        assert!(b.min.cmple(q.min).all() && b.max.cmpge(q.max).all());
                        seen[source as usize] += 1;
                    }
                }
            }
            assert!(seen.iter().all(|&s| s == 1));
            assert!(packed.depth >= 1);
        }
    }

    #[test]
    fn empty_trees_have_no_root() {
        let mut out = Vec::new();
        let tree = build(Vec::new());
        assert_eq!(pack_tree(&tree.nodes, 0, &mut out).root, EMPTY);
        assert!(out.is_empty());
    }
}
