//! Multi-threaded binned-SAH construction of a flattened binary BVH.
//!
//! Each node is split by evaluating the surface area heuristic over
//! [`BINS`] centroid bins on all three axes; nodes above [`PARALLEL_MIN`]
//! primitives bin in parallel and the top [`PARALLEL_DEPTH`] levels build
//! their two subtrees with `rayon::join`. Below that a sequential builder
//! with an explicit stack takes over, so degenerate inputs cannot overflow
//! the call stack.

use glam::Vec3;
use rayon::prelude::*;

use super::{Aabb, BvhNode};

/// Number of centroid bins per axis.
const BINS: usize = 16;
/// Largest leaf the builder produces.
const MAX_LEAF: usize = 8;
/// Cost of traversing one node, relative to one primitive test.
pub const TRAVERSAL_COST: f32 = 1.0;
/// Cost of one primitive intersection test.
pub const INTERSECTION_COST: f32 = 1.0;
/// Nodes with at least this many primitives bin in parallel.
const PARALLEL_MIN: usize = 1 << 16;
/// Subtrees are built concurrently down to this depth.
const PARALLEL_DEPTH: u32 = 8;
/// Subtrees smaller than this are never forked.
const FORK_MIN: usize = 4096;

/// A primitive reference: its bounds and its index in the source list.
#[derive(Clone, Copy, Debug)]
pub struct PrimRef {
    /// Smallest corner of the primitive bounds.
    pub min: Vec3,
    /// Index of the primitive in the caller's list.
    pub index: u32,
    /// Largest corner of the primitive bounds.
    pub max: Vec3,
}

impl PrimRef {
    /// A reference to primitive `index` with bounds `b`.
    pub fn new(b: &Aabb, index: u32) -> Self {
        Self {
            min: b.min,
            index,
            max: b.max,
        }
    }

    fn centroid(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    fn bounds(&self) -> Aabb {
        Aabb::new(self.min, self.max)
    }
}

/// A built tree: flattened nodes (root first) and the primitive order the
/// leaves index into.
pub struct BuiltTree {
    /// Nodes; the root is node 0.
    pub nodes: Vec<BvhNode>,
    /// `order[i]` is the source index of the i-th primitive in leaf order.
    pub order: Vec<u32>,
}

/// Bounds of a node's primitives and of their centroids.
#[derive(Clone, Copy)]
struct Extent {
    bounds: Aabb,
    centroids: Aabb,
}

impl Extent {
    const EMPTY: Extent = Extent {
        bounds: Aabb::EMPTY,
        centroids: Aabb::EMPTY,
    };

    fn add(&mut self, p: &PrimRef) {
        self.bounds = self.bounds.union(p.bounds());
        self.centroids = self.centroids.grown_by_point(p.centroid());
    }

    fn merge(self, o: Extent) -> Extent {
        Extent {
            bounds: self.bounds.union(o.bounds),
            centroids: self.centroids.union(o.centroids),
        }
    }

    fn of(prims: &[PrimRef]) -> Extent {
        if prims.len() >= PARALLEL_MIN {
            prims
                .par_chunks(PARALLEL_MIN / 4)
                .map(Extent::of)
                .reduce(|| Extent::EMPTY, Extent::merge)
        } else {
            let mut e = Extent::EMPTY;
            prims.iter().for_each(|p| e.add(p));
            e
        }
    }
}

/// Per-axis bin contents: primitive bounds and counts.
#[derive(Clone, Copy)]
struct Bins {
    bounds: [[Aabb; BINS]; 3],
    count: [[u32; BINS]; 3],
}

/// Maps centroids to bin indices along each axis.
#[derive(Clone, Copy)]
struct Binner {
    origin: Vec3,
    scale: Vec3,
    bins: usize,
}

impl Binner {
    fn new(centroids: &Aabb, bins: usize) -> Self {
        let e = centroids.extent();
        let scale = Vec3::select(
            e.cmpgt(Vec3::ZERO),
            Vec3::splat(bins as f32) / e,
            Vec3::ZERO,
        );
        Self {
            origin: centroids.min,
            scale,
            bins,
        }
    }

    fn bin(&self, c: Vec3, axis: usize) -> usize {
        (((c[axis] - self.origin[axis]) * self.scale[axis]) as usize).min(self.bins - 1)
    }
}

impl Bins {
    fn empty() -> Self {
        Self {
            bounds: [[Aabb::EMPTY; BINS]; 3],
            count: [[0; BINS]; 3],
        }
    }

    fn fill(binner: &Binner, prims: &[PrimRef]) -> Self {
        if prims.len() >= PARALLEL_MIN {
            return prims
                .par_chunks(PARALLEL_MIN / 4)
                .map(|c| Bins::fill(binner, c))
                .reduce(Bins::empty, Bins::merge);
        }
        let mut bins = Bins::empty();
        for p in prims {
            let c = p.centroid();
            let b = p.bounds();
            for axis in 0..3 {
                let k = binner.bin(c, axis);
                bins.bounds[axis][k] = bins.bounds[axis][k].union(b);
                bins.count[axis][k] += 1;
            }
        }
        bins
    }

    fn merge(mut self, o: Bins) -> Bins {
        for axis in 0..3 {
            for b in 0..BINS {
                self.bounds[axis][b] = self.bounds[axis][b].union(o.bounds[axis][b]);
                self.count[axis][b] += o.count[axis][b];
            }
        }
        self
    }
}

/// The chosen split of a node.
struct Split {
    axis: usize,
    /// Primitives in bins `< bin` go left.
    bin: usize,
    cost: f32,
    left: Aabb,
    right: Aabb,
}

fn best_split(binner: &Binner, bins: &Bins, parent_area: f32) -> Option<Split> {
    let nb = binner.bins;
    let mut best: Option<Split> = None;
    for axis in 0..3 {
        if binner.scale[axis] == 0.0 {
            continue;
        }
        // Suffix sweep: right bounds, areas and counts for every split.
        let mut right = [Aabb::EMPTY; BINS];
        let mut right_count = [0u32; BINS];
        let mut acc = Aabb::EMPTY;
        let mut n = 0;
        for b in (1..nb).rev() {
            acc = acc.union(bins.bounds[axis][b]);
            n += bins.count[axis][b];
            right[b] = acc;
            right_count[b] = n;
        }
        let mut left = Aabb::EMPTY;
        let mut left_count = 0;
        for b in 1..nb {
            left = left.union(bins.bounds[axis][b - 1]);
            left_count += bins.count[axis][b - 1];
            if left_count == 0 || right_count[b] == 0 {
                continue;
            }
            let cost = TRAVERSAL_COST
                + INTERSECTION_COST
                    * (left.surface_area() * left_count as f32
                        + right[b].surface_area() * right_count[b] as f32)
                    / parent_area.max(f32::MIN_POSITIVE);
            if best.as_ref().is_none_or(|s| cost < s.cost) {
                best = Some(Split {
                    axis,
                    bin: b,
                    cost,
                    left,
                    right: right[b],
                });
            }
        }
    }
    best
}

/// What to do with a node.
enum Decision {
    Leaf,
    Split(usize, Extent, Extent),
}

/// Decides a node's fate and partitions its primitives in place.
fn decide(prims: &mut [PrimRef], extent: &Extent) -> Decision {
    let n = prims.len();
    if n <= 1 {
        return Decision::Leaf;
    }
    let binner = Binner::new(&extent.centroids, n.clamp(4, BINS));
    let bins = Bins::fill(&binner, prims);
    let leaf_cost = INTERSECTION_COST * n as f32;
    match best_split(&binner, &bins, extent.bounds.surface_area()) {
        Some(s) if s.cost < leaf_cost || n > MAX_LEAF => {
            let (mid, lc, rc) = partition(prims, |c| binner.bin(c, s.axis) < s.bin);
            Decision::Split(
                mid,
                Extent {
                    bounds: s.left,
                    centroids: lc,
                },
                Extent {
                    bounds: s.right,
                    centroids: rc,
                },
            )
        }
        Some(_) => Decision::Leaf,
        None if n <= MAX_LEAF => Decision::Leaf,
        None => {
            // All centroids coincide: split by count.
            let mid = n / 2;
            Decision::Split(mid, Extent::of(&prims[..mid]), Extent::of(&prims[mid..]))
        }
    }
}

/// Partitions by centroid, returning the split point and the centroid
/// bounds of both sides.
fn partition(prims: &mut [PrimRef], goes_left: impl Fn(Vec3) -> bool) -> (usize, Aabb, Aabb) {
    let (mut lc, mut rc) = (Aabb::EMPTY, Aabb::EMPTY);
    let mut i = 0;
    let mut j = prims.len();
    while i < j {
        let c = prims[i].centroid();
        if goes_left(c) {
            lc = lc.grown_by_point(c);
            i += 1;
        } else {
            rc = rc.grown_by_point(c);
            j -= 1;
            prims.swap(i, j);
        }
    }
    (i, lc, rc)
}

/// Builds a BVH over `prims` (consumed; their order becomes the leaf order).
pub fn build(mut prims: Vec<PrimRef>) -> BuiltTree {
    if prims.is_empty() {
        return BuiltTree {
            nodes: vec![BvhNode::leaf(&Aabb::new(Vec3::ZERO, Vec3::ZERO), 0, 0)],
            order: Vec::new(),
        };
    }
    let extent = Extent::of(&prims);
    let nodes = build_subtree(&mut prims, 0, extent, 0);
    BuiltTree {
        nodes,
        order: prims.iter().map(|p| p.index).collect(),
    }
}

/// Builds the subtree over `prims` (which start at `offset` in the final
/// order) into its own node list, root first.
fn build_subtree(prims: &mut [PrimRef], offset: u32, extent: Extent, depth: u32) -> Vec<BvhNode> {
    if depth >= PARALLEL_DEPTH || prims.len() < FORK_MIN {
        return build_sequential(prims, offset, extent);
    }
    match decide(prims, &extent) {
        Decision::Leaf => vec![BvhNode::leaf(&extent.bounds, offset, prims.len() as u32)],
        Decision::Split(mid, le, re) => {
            let (lp, rp) = prims.split_at_mut(mid);
            let (left, right) = rayon::join(
                || build_subtree(lp, offset, le, depth + 1),
                || build_subtree(rp, offset + mid as u32, re, depth + 1),
            );
            merge(&extent.bounds, left, right)
        }
    }
}

/// Joins two independently built subtrees under a new root. The children
/// roots go to slots 1 and 2, followed by the left and then the right
/// descendants, with child links relocated.
fn merge(bounds: &Aabb, left: Vec<BvhNode>, right: Vec<BvhNode>) -> Vec<BvhNode> {
    let left_len = left.len() as u32;
    let relocate = |mut n: BvhNode, shift: u32| {
        if !n.is_leaf() {
            n.left_or_first += shift;
        }
        n
    };
    let mut out = Vec::with_capacity(1 + left.len() + right.len());
    out.push(BvhNode::interior(bounds, 1));
    out.push(relocate(left[0], 2));
    out.push(relocate(right[0], 1 + left_len));
    out.extend(left[1..].iter().map(|&n| relocate(n, 2)));
    out.extend(right[1..].iter().map(|&n| relocate(n, 1 + left_len)));
    out
}

fn build_sequential(prims: &mut [PrimRef], offset: u32, extent: Extent) -> Vec<BvhNode> {
    let mut nodes = vec![BvhNode::default()];
    // (node slot, first primitive, primitive count, extent)
    let mut stack = vec![(0usize, 0usize, prims.len(), extent)];
    while let Some((slot, first, count, ext)) = stack.pop() {
        let range = &mut prims[first..first + count];
        match decide(range, &ext) {
            Decision::Leaf => {
                nodes[slot] = BvhNode::leaf(&ext.bounds, offset + first as u32, count as u32);
            }
            Decision::Split(mid, le, re) => {
                let left = nodes.len();
                nodes[slot] = BvhNode::interior(&ext.bounds, left as u32);
                nodes.push(BvhNode::default());
                nodes.push(BvhNode::default());
                stack.push((left + 1, first + mid, count - mid, re));
                stack.push((left, first, mid, le));
            }
        }
    }
    nodes
}

/// The SAH cost of a tree: expected traversal plus intersection cost of a
/// random ray hitting the root, normalised by the root surface area.
pub fn sah_cost(nodes: &[BvhNode]) -> f32 {
    let root_area = nodes.first().map_or(0.0, |n| n.bounds().surface_area());
    if root_area <= 0.0 {
        return nodes
            .first()
            .map_or(0.0, |n| n.count as f32 * INTERSECTION_COST);
    }
    nodes
        .iter()
        .map(|n| {
            let area = n.bounds().surface_area() / root_area;
            if n.is_leaf() {
                area * n.count as f32 * INTERSECTION_COST
            } else {
                area * TRAVERSAL_COST
            }
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid_prims(n: u32) -> Vec<PrimRef> {
        (0..n)
            .map(|i| {
                let p = Vec3::new((i % 97) as f32, (i / 97 % 89) as f32, (i * 7 % 13) as f32);
                PrimRef::new(&Aabb::new(p, p + Vec3::splat(0.5)), i)
            })
            .collect()
    }

    /// Every primitive appears in exactly one leaf, and every node bounds
    /// its children / primitives.
    fn check(prims: &[PrimRef], tree: &BuiltTree) {
        let mut seen = vec![0u32; prims.len()];
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let n = tree.nodes[i];
            let b = n.bounds();
            if n.is_leaf() {
                for k in n.left_or_first..n.left_or_first + n.count {
                    let p = &prims[tree.order[k as usize] as usize];
                    assert!(b.min.cmple(p.min).all() && b.max.cmpge(p.max).all());
                    seen[tree.order[k as usize] as usize] += 1;
                }
            } else {
                for c in [n.left_or_first, n.left_or_first + 1] {
                    let cb = tree.nodes[c as usize].bounds();
                    assert!(b.min.cmple(cb.min).all() && b.max.cmpge(cb.max).all());
                    stack.push(c as usize);
                }
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
    }

    #[test]
    fn builds_valid_trees_sequential_and_parallel() {
        for n in [1, 2, 9, 1000, 20_000] {
            let prims = grid_prims(n);
            let tree = build(prims.clone());
            check(&prims, &tree);
            assert!(sah_cost(&tree.nodes) > 0.0);
        }
    }

    #[test]
    fn identical_primitives_split_by_count() {
        let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let prims: Vec<_> = (0..100).map(|i| PrimRef::new(&b, i)).collect();
        let tree = build(prims.clone());
        check(&prims, &tree);
        assert!(tree.nodes.iter().all(|n| n.count as usize <= MAX_LEAF));
    }
}
