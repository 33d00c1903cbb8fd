//! Packs vertices, triangles and bottom-level nodes.

use glam::Vec2;

use super::encode::{encode_color, encode_normal, encode_uv};
use super::layout::{GpuSphere, GpuTriangle, GpuVertex, GpuVertexAttributes};
use super::nodes::{BvhLayout, GpuNodes, PackedTree};
use crate::scene::{Bvh, Mesh, Scene};

/// Vertex `i`'s colour and alpha, and its tangent with the bitangent's sign.
fn attributes(mesh: &Mesh, i: usize) -> GpuVertexAttributes {
    let color = mesh.colors.get(i).copied().unwrap_or(glam::Vec3::ONE);
    let alpha = mesh.alphas.get(i).copied().unwrap_or(1.0);
    let tangent = mesh
        .tangents
        .get(i)
        .copied()
        .unwrap_or(glam::Vec4::X.with_w(1.0));
    let [rg, b] = encode_color(color.extend(alpha));
    [
        rg,
        b,
        encode_normal(tangent.truncate()),
        tangent.w.to_bits(),
    ]
}

/// Packed geometry and bottom levels.
pub struct PackedGeometry {
    /// All mesh vertices, mesh after mesh.
    pub vertices: Vec<GpuVertex>,
    /// The colour, alpha and tangent of every vertex of `vertices` (opaque white and `+X` where a
    /// mesh has none) when some mesh has vertex colours or tangents, else empty.
    pub vertex_attributes: Vec<GpuVertexAttributes>,
    /// Every triangle's vertex, edges and vertex indices (absolute), each mesh's triangles in its
    /// packed BLAS's order (`blas_orders`).
    pub triangles: Vec<GpuTriangle>,
    /// All BLAS nodes in the GPU layout, with absolute node and triangle indices.
    pub blas_nodes: GpuNodes,
    /// Root of each BLAS (same order as `Bvh::blases`; see [`super::nodes::PackedTree::root`]).
    pub blas_roots: Vec<u32>,
    /// Per BLAS, the source primitive of each packed primitive.
    pub blas_orders: Vec<Vec<u32>>,
    /// Nodes on the longest root-to-leaf path of any BLAS.
    pub blas_depth: u32,
    /// First global triangle of each mesh.
    pub triangle_base: Vec<u32>,
    /// Spheres in the packed sphere BLAS's order.
    pub spheres: Vec<GpuSphere>,
}

/// Packs all meshes and spheres of `scene` with the BLASes of `bvh` in `layout`.
pub fn pack(scene: &Scene, bvh: &Bvh, layout: BvhLayout) -> PackedGeometry {
    let vertex_total: usize = scene.meshes.iter().map(|m| m.positions.len()).sum();
    let attributed = scene
        .meshes
        .iter()
        .any(|m| !m.colors.is_empty() || !m.tangents.is_empty());
    let mut out = PackedGeometry {
        vertices: Vec::with_capacity(vertex_total),
        vertex_attributes: Vec::new(),
        triangles: Vec::with_capacity(scene.unique_triangle_count()),
        blas_nodes: GpuNodes::new(layout),
        blas_roots: Vec::with_capacity(bvh.blases.len()),
        blas_orders: Vec::with_capacity(bvh.blases.len()),
        blas_depth: 0,
        triangle_base: Vec::with_capacity(scene.meshes.len()),
        spheres: Vec::new(),
    };
    for (mesh, blas) in scene.meshes.iter().zip(&bvh.blases) {
        let vertex_base = out.vertices.len() as u32;
        out.vertices
            .extend(mesh.positions.iter().enumerate().map(|(i, p)| GpuVertex {
                position: p.to_array(),
                normal: encode_normal(mesh.normals[i]),
                uv: encode_uv(mesh.uvs.get(i).copied().unwrap_or(Vec2::ZERO)),
            }));
        if attributed {
            out.vertex_attributes
                .extend((0..mesh.positions.len()).map(|i| attributes(mesh, i)));
        }
        let tri_base = out.triangles.len() as u32;
        out.triangle_base.push(tri_base);
        let packed = out.blas_nodes.pack_tree(&blas.nodes, &blas.order, tri_base);
        out.triangles.extend(packed.order.iter().map(|&t| {
            let [p0, p1, p2] = mesh.triangle(t as usize);
            GpuTriangle {
                p0: p0.to_array(),
                e1: (p1 - p0).to_array(),
                e2: (p2 - p0).to_array(),
                vertices: (mesh.indices[t as usize] + vertex_base).to_array(),
            }
        }));
        out.add_blas(packed);
    }
    if let Some(blas) = bvh.blases.get(scene.meshes.len()) {
        let packed = out.blas_nodes.pack_tree(&blas.nodes, &blas.order, 0);
        out.spheres = packed
            .order
            .iter()
            .map(|&s| {
                let sp = &scene.spheres[s as usize];
                GpuSphere {
                    center_radius: sp.center.extend(sp.radius).to_array(),
                    material: sp.material,
                    scene_sphere: s,
                    pad: [0; 2],
                }
            })
            .collect();
        out.add_blas(packed);
    }
    out
}

impl PackedGeometry {
    /// Records a packed BLAS's root, order and depth.
    fn add_blas(&mut self, packed: PackedTree) {
        self.blas_roots.push(packed.root);
        self.blas_orders.push(packed.order);
        self.blas_depth = self.blas_depth.max(packed.depth);
    }
}
