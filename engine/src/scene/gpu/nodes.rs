//! The two GPU BVH layouts behind one interface: which one a scene is packed in, its node buffers,
//! and packing a tree in either.

use std::fmt;

use super::bvh_pack::{self, GpuBvhNode};
use super::wide::{self, WideNode};
use super::BvhDepths;
use crate::bvh::BvhNode;

/// How the GPU's BVH nodes are laid out (the shaders' `WIDE_BVH` specialization constant). With the
/// `clap` feature, a `clap::ValueEnum` of its names.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum BvhLayout {
    /// Binary nodes holding both children's boxes as floats (64 bytes, [`bvh_pack`]): the default,
    /// faster on an H100 for every built-in scene (`bench/README.md`).
    #[default]
    Binary,
    /// Compressed 8-wide nodes with byte-quantized child boxes (80 bytes, [`wide`]).
    Wide,
}

impl BvhLayout {
    /// Both layouts.
    pub const ALL: [BvhLayout; 2] = [BvhLayout::Binary, BvhLayout::Wide];

    /// The deepest trees (nodes on the longest root-to-leaf path) the GPU walks of this layout can
    /// stack for (`shaders/common/traverse_binary.glsl`'s `BLAS_STACK` and `TLAS_STACK`: one entry
    /// per interior node of a path; `traverse_wide.glsl`'s `WIDE_STACK`: one per node below the
    /// root).
    pub fn max_depths(self) -> BvhDepths {
        match self {
            BvhLayout::Binary => BvhDepths { blas: 40, tlas: 24 },
            BvhLayout::Wide => BvhDepths { blas: 33, tlas: 33 },
        }
    }

    /// The name on the command line and in reports (`binary`, `wide`).
    pub fn name(self) -> &'static str {
        match self {
            BvhLayout::Binary => "binary",
            BvhLayout::Wide => "wide",
        }
    }
}

impl fmt::Display for BvhLayout {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The nodes of one BVH level (all bottom levels, or the top level) in one layout.
#[derive(Clone, Debug, PartialEq)]
pub enum GpuNodes {
    /// Binary nodes.
    Binary(Vec<GpuBvhNode>),
    /// Wide nodes.
    Wide(Vec<WideNode>),
}

impl Default for GpuNodes {
    fn default() -> Self {
        GpuNodes::new(BvhLayout::default())
    }
}

impl GpuNodes {
    /// No nodes, in `layout`.
    pub fn new(layout: BvhLayout) -> Self {
        match layout {
            BvhLayout::Binary => GpuNodes::Binary(Vec::new()),
            BvhLayout::Wide => GpuNodes::Wide(Vec::new()),
        }
    }

    /// The layout.
    pub fn layout(&self) -> BvhLayout {
        match self {
            GpuNodes::Binary(_) => BvhLayout::Binary,
            GpuNodes::Wide(_) => BvhLayout::Wide,
        }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        match self {
            GpuNodes::Binary(n) => n.len(),
            GpuNodes::Wide(n) => n.len(),
        }
    }

    /// Whether there are no nodes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The nodes as uploaded.
    pub fn bytes(&self) -> &[u8] {
        match self {
            GpuNodes::Binary(n) => bytemuck::cast_slice(n),
            GpuNodes::Wide(n) => bytemuck::cast_slice(n),
        }
    }

    /// Appends the flattened binary tree `nodes` (root first, as built by [`crate::bvh`]) whose
    /// leaves index `order` (source primitive of each leaf-order position); the packed leaves name
    /// primitives from `prim_base`.
    pub fn pack_tree(&mut self, nodes: &[BvhNode], order: &[u32], prim_base: u32) -> PackedTree {
        match self {
            GpuNodes::Binary(out) => PackedTree {
                root: bvh_pack::pack_tree(nodes, prim_base, out),
                order: order.to_vec(),
                depth: binary_depth(nodes),
            },
            GpuNodes::Wide(out) => {
                let packed = wide::pack_tree(nodes, prim_base, out);
                PackedTree {
                    root: packed.root,
                    order: packed.order.iter().map(|&p| order[p as usize]).collect(),
                    depth: packed.depth,
                }
            }
        }
    }
}

/// One tree packed into [`GpuNodes`].
#[derive(Clone, Debug, PartialEq)]
pub struct PackedTree {
    /// What the traversal starts from: a binary child word ([`bvh_pack`]) or a wide root node
    /// index ([`wide::EMPTY`] and [`bvh_pack::EMPTY`] are both `u32::MAX`).
    pub root: u32,
    /// The source primitive of each packed primitive (from `prim_base`).
    pub order: Vec<u32>,
    /// Nodes on the longest root-to-leaf path of the packed tree.
    pub depth: u32,
}

/// Interior nodes on the longest path of a flattened binary tree (the packed binary layout keeps
/// only interior nodes; leaves are child words).
fn binary_depth(nodes: &[BvhNode]) -> u32 {
    let mut depth = vec![0u32; nodes.len()];
    let mut deepest = 0;
    for (i, n) in nodes.iter().enumerate() {
        if !n.is_leaf() && n.left_or_first != 0 {
            let d = depth[i] + 1;
            deepest = deepest.max(d);
            let l = n.left_or_first as usize;
            depth[l] = d;
            depth[l + 1] = d;
        }
    }
    deepest
}
