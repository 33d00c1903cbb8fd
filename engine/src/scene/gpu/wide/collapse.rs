//! Which binary nodes become the children of a wide node: greedy largest-surface-area collapse.
//!
//! Starting from a binary node's two children, the inner child with the largest surface area is
//! replaced by its two children while the node's slots allow (a ray that reaches the node is the
//! likelier to reach a larger box, so opening it saves the most node visits). A binary subtree of
//! at most [`MAX_LEAF_PRIMITIVES`] primitives becomes one leaf slot; a binary leaf of more takes
//! several slots with the leaf's box.

use crate::bvh::{Aabb, BvhNode};

use super::node::{MAX_LEAF_PRIMITIVES, WIDTH};

/// A child of a wide node, in terms of the binary tree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Child {
    /// Binary node `index`, which becomes a wide node.
    Inner {
        /// The binary node.
        index: u32,
        /// Its box.
        bounds: Aabb,
    },
    /// `count` primitives from `first` of the binary tree's leaf order.
    Leaf {
        /// First primitive (leaf-order position).
        first: u32,
        /// 1 to [`MAX_LEAF_PRIMITIVES`] primitives.
        count: u32,
        /// Their box (the binary node's).
        bounds: Aabb,
    },
}

impl Child {
    /// The child's box.
    pub fn bounds(&self) -> Aabb {
        match *self {
            Child::Inner { bounds, .. } | Child::Leaf { bounds, .. } => bounds,
        }
    }
}

/// A binary tree with each node's primitive range, for collapsing.
pub struct Collapser<'a> {
    nodes: &'a [BvhNode],
    /// Per binary node: first leaf-order position and number of primitives of its subtree.
    ranges: Vec<(u32, u32)>,
}

impl<'a> Collapser<'a> {
    /// Prepares the flattened binary tree `nodes` (root first, children after their parents, as
    /// `crate::bvh::build` lays them out; not empty).
    pub fn new(nodes: &'a [BvhNode]) -> Self {
        let mut ranges = vec![(0u32, 0u32); nodes.len()];
        for (i, n) in nodes.iter().enumerate().rev() {
            ranges[i] = if n.is_leaf() {
                (n.left_or_first, n.count)
            } else {
                let l = n.left_or_first as usize;
                debug_assert!(l > i, "children follow their parent");
                let (first, a) = ranges[l];
                (first, a + ranges[l + 1].1)
            };
        }
        Self { nodes, ranges }
    }

    /// Primitives under binary node `index`.
    pub fn count(&self, index: u32) -> u32 {
        self.ranges[index as usize].1
    }

    /// Whether binary node `index` becomes leaf slots rather than a wide node.
    fn is_leaf(&self, index: u32) -> bool {
        self.nodes[index as usize].is_leaf() || self.count(index) <= MAX_LEAF_PRIMITIVES
    }

    /// Slots binary node `index` takes as a child.
    fn slots(&self, index: u32) -> usize {
        if self.is_leaf(index) {
            self.count(index).div_ceil(MAX_LEAF_PRIMITIVES) as usize
        } else {
            1
        }
    }

    /// The children of the wide node standing for binary node `index` (at most [`WIDTH`]).
    pub fn children(&self, index: u32) -> Vec<Child> {
        // (binary node, whether it may still be opened); their order does not matter (the
        // children take slots by position later).
        let mut open = [(0u32, false); WIDTH];
        let mut len = if self.is_leaf(index) {
            open[0] = (index, false);
            1
        } else {
            let l = self.nodes[index as usize].left_or_first;
            open[0] = (l, true);
            open[1] = (l + 1, true);
            2
        };
        let mut used: usize = open[..len].iter().map(|&(i, _)| self.slots(i)).sum();
        let area = |i: u32| self.nodes[i as usize].bounds().surface_area();
        while let Some(k) = open[..len]
            .iter()
            .enumerate()
            .filter(|(_, &(i, may_open))| may_open && !self.is_leaf(i))
            .max_by(|a, b| area(a.1 .0).total_cmp(&area(b.1 .0)))
            .map(|(k, _)| k)
        {
            let l = self.nodes[open[k].0 as usize].left_or_first;
            let after = used - 1 + self.slots(l) + self.slots(l + 1);
            if after > WIDTH {
                open[k].1 = false;
                continue;
            }
            used = after;
            open[k] = (l, true);
            open[len] = (l + 1, true);
            len += 1;
        }
        let mut children = Vec::with_capacity(WIDTH);
        for &(i, _) in &open[..len] {
            let bounds = self.nodes[i as usize].bounds();
            if !self.is_leaf(i) {
                children.push(Child::Inner { index: i, bounds });
                continue;
            }
            let (first, count) = self.ranges[i as usize];
            let pieces = count.div_ceil(MAX_LEAF_PRIMITIVES);
            let mut start = first;
            for p in 0..pieces {
                let n = count / pieces + u32::from(p < count % pieces);
                children.push(Child::Leaf {
                    first: start,
                    count: n,
                    bounds,
                });
                start += n;
            }
        }
        debug_assert!(children.len() <= WIDTH);
        children
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::build::{build, PrimRef};
    use glam::Vec3;

    fn tree(n: u32) -> Vec<BvhNode> {
        let prims = (0..n)
            .map(|i| {
                let p = Vec3::new((i % 31) as f32, (i / 31 % 17) as f32, (i * 5 % 11) as f32);
                PrimRef::new(&Aabb::new(p, p + Vec3::splat(0.4)), i)
            })
            .collect();
        build(prims).nodes
    }

    /// Every primitive is reached exactly once from the root through the collapsed children.
    #[test]
    fn collapsed_children_cover_every_primitive_once() {
        for n in [1, 2, 3, 4, 7, 50, 3000] {
            let nodes = tree(n);
            let c = Collapser::new(&nodes);
            let mut seen = vec![0u32; n as usize];
            let mut stack = vec![0u32];
            let mut wide_nodes = 0;
            while let Some(i) = stack.pop() {
                wide_nodes += 1;
                let children = c.children(i);
                assert!(!children.is_empty() && children.len() <= WIDTH);
                for child in children {
                    match child {
                        Child::Inner { index, .. } => stack.push(index),
                        Child::Leaf { first, count, .. } => {
                            assert!((1..=MAX_LEAF_PRIMITIVES).contains(&count));
                            for p in first..first + count {
                                seen[p as usize] += 1;
                            }
                        }
                    }
                }
            }
            assert!(seen.iter().all(|&s| s == 1), "{n} primitives");
            if n >= 3000 {
                // Wide nodes fill up: far fewer than binary interior nodes.
                assert!(
                    wide_nodes * 4 < nodes.len(),
                    "{wide_nodes} of {}",
                    nodes.len()
                );
            }
        }
    }
}
