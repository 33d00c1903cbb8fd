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

use rayon::prelude::*;

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

/// Subtrees over at least this many primitives pack their inner children's subtrees in parallel.
const PARALLEL_MIN: u32 = 1 << 15;

/// Appends the wide form of the flattened binary tree `nodes` (root first, as built by
/// [`crate::bvh`]) to `out`; its leaves name primitives from `prim_base`. Each node's inner
/// children are stored contiguously; subtrees are laid out depth first (large ones packed in
/// parallel, then concatenated).
pub fn pack_tree(nodes: &[BvhNode], prim_base: u32, out: &mut Vec<WideNode>) -> PackedWide {
    match nodes.first() {
        None => return empty(),
        Some(root) if !root.is_leaf() && root.left_or_first == 0 => return empty(),
        Some(_) => {}
    }
    let collapser = Collapser::new(nodes);
    let tree = pack_subtree(&collapser, 0);
    let root = out.len() as u32;
    out.extend(tree.nodes.iter().map(|n| relocated(n, root, prim_base)));
    PackedWide {
        root,
        order: tree.order,
        depth: tree.depth,
    }
}

/// A subtree packed on its own: its root is node 0, its primitives start at 0.
struct Subtree {
    nodes: Vec<WideNode>,
    order: Vec<u32>,
    depth: u32,
}

/// `node` with its child indices shifted by `nodes` and its primitive indices by `primitives`.
fn relocated(node: &WideNode, nodes: u32, primitives: u32) -> WideNode {
    WideNode {
        child_base: node.child_base + nodes,
        primitive_base: node.primitive_base + primitives,
        ..*node
    }
}

/// One wide node's plan: its slots (leaf offsets from 0), the binary nodes of its inner children
/// in slot order, and the leaf-order positions of its leaf children's primitives in slot order.
struct NodePlan {
    slots: [Slot; WIDTH],
    inner: Vec<u32>,
    primitives: Vec<u32>,
}

/// Collapses binary node `binary` into one wide node's children and places them in slots.
fn plan(collapser: &Collapser, binary: u32) -> NodePlan {
    let children = collapser.children(binary);
    let centers: Vec<_> = children.iter().map(|c| c.bounds().center()).collect();
    let center = children
        .iter()
        .fold(crate::bvh::Aabb::EMPTY, |b, c| b.union(c.bounds()))
        .center();
    let mut plan = NodePlan {
        slots: [Slot::Empty; WIDTH],
        inner: Vec::new(),
        primitives: Vec::new(),
    };
    for (s, child) in slots::assign(&centers, center).iter().enumerate() {
        let Some(k) = *child else { continue };
        plan.slots[s] = match children[k] {
            Child::Inner { index, bounds } => {
                plan.inner.push(index);
                Slot::Inner(bounds)
            }
            Child::Leaf {
                first,
                count,
                bounds,
            } => {
                let offset = plan.primitives.len() as u32;
                plan.primitives.extend(first..first + count);
                Slot::Leaf {
                    bounds,
                    offset,
                    count,
                }
            }
        };
    }
    plan
}

/// Packs the subtree of binary node `binary`: large ones with their inner children's subtrees in
/// parallel, small ones sequentially.
fn pack_subtree(collapser: &Collapser, binary: u32) -> Subtree {
    if collapser.count(binary) < PARALLEL_MIN {
        return pack_sequential(collapser, binary);
    }
    let plan = plan(collapser, binary);
    let subtrees: Vec<Subtree> = plan
        .inner
        .par_iter()
        .map(|&b| pack_subtree(collapser, b))
        .collect();
    // The root, its inner children's roots, then each child's other nodes.
    let inner = subtrees.len() as u32;
    let mut nodes = vec![WideNode::new(&plan.slots, 1, 0)];
    let mut order = plan.primitives;
    let mut offsets = Vec::with_capacity(subtrees.len());
    let mut next = 1 + inner;
    for t in &subtrees {
        offsets.push((next, order.len() as u32));
        next += t.nodes.len() as u32 - 1;
        order.extend(&t.order);
    }
    for (t, &(at, primitives)) in subtrees.iter().zip(&offsets) {
        nodes.push(relocated(&t.nodes[0], at - 1, primitives));
    }
    for (t, &(at, primitives)) in subtrees.iter().zip(&offsets) {
        nodes.extend(
            t.nodes[1..]
                .iter()
                .map(|n| relocated(n, at - 1, primitives)),
        );
    }
    let depth = 1 + subtrees.iter().map(|t| t.depth).max().unwrap_or(0);
    Subtree {
        nodes,
        order,
        depth,
    }
}

/// Packs the subtree of binary node `binary` on this thread, depth first.
fn pack_sequential(collapser: &Collapser, binary: u32) -> Subtree {
    let mut tree = Subtree {
        nodes: vec![WideNode::default()],
        order: Vec::new(),
        depth: 0,
    };
    // (wide node, binary node, depth)
    let mut stack = vec![(0u32, binary, 1u32)];
    while let Some((at, binary, level)) = stack.pop() {
        tree.depth = tree.depth.max(level);
        let plan = plan(collapser, binary);
        let child_base = tree.nodes.len() as u32;
        let primitive_base = tree.order.len() as u32;
        tree.order.extend(&plan.primitives);
        tree.nodes[at as usize] = WideNode::new(&plan.slots, child_base, primitive_base);
        tree.nodes
            .resize(tree.nodes.len() + plan.inner.len(), WideNode::default());
        for (r, &index) in plan.inner.iter().enumerate().rev() {
            stack.push((child_base + r as u32, index, level + 1));
        }
    }
    tree
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
        // 100 000 primitives take the parallel path (PARALLEL_MIN).
        for n in [1, 2, 5, 9, 2000, 100_000] {
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
