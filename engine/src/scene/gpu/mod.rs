//! The packed, GPU-ready form of a scene: plain `Vec<T: Pod>` arrays that
//! upload 1:1 into storage buffers.
//!
//! Buffers and how they reference each other:
//! - `vertices` ([`GpuVertex`], 20 B) and `indices` (3 × `u32` per
//!   triangle, absolute vertex indices). Each mesh's triangles are stored
//!   in its BLAS leaf order, so a BLAS leaf `(first, count)` is directly a
//!   global triangle range.
//! - `blas_nodes` / `tlas_nodes` ([`BvhNode`], 32 B, see `crate::bvh`):
//!   all BLASes concatenated with absolute child indices; TLAS leaves index
//!   `instances`, which are stored in TLAS leaf order.
//! - `instances` ([`GpuInstance`]): transforms, BLAS root, material.
//! - `spheres` ([`GpuSphere`]) in sphere-BLAS leaf order.
//! - `materials`, `textures` (records into the flat `texels` word buffer).
//! - `lights` + `light_table`: the NEE light list with its power-based
//!   alias table / CDF.
//! - `params`: camera, environment, sun, counts.

mod encode;
mod flat;
mod geometry;
mod layout;
mod params;

pub use encode::{decode_normal, encode_normal, encode_uv};
pub use flat::{fix_instances, pack_flat, INSTANCE_FLATTENED};
pub use layout::{
    light_kind, material_kind, texture_format, GpuAliasEntry, GpuCamera, GpuEnvironment,
    GpuInstance, GpuLight, GpuMaterial, GpuSceneParams, GpuSphere, GpuSun, GpuTextureRecord,
    GpuTriangle, GpuVertex,
};
pub use params::camera;

use std::mem::size_of;

use glam::Affine3A;

use super::{LightDistribution, Scene, SceneFeatures};
use crate::bvh::{Bvh, BvhNode, InstanceSource};

/// Everything the GPU passes need, CPU side.
#[derive(Clone, Debug, Default)]
pub struct GpuScene {
    /// Mesh vertices.
    pub vertices: Vec<GpuVertex>,
    /// Triangle vertex indices, three per triangle.
    pub indices: Vec<u32>,
    /// Triangles for ray intersection (first vertex and edges), in the order of `indices`.
    pub triangles: Vec<GpuTriangle>,
    /// All bottom-level nodes.
    pub blas_nodes: Vec<BvhNode>,
    /// Top-level nodes.
    pub tlas_nodes: Vec<BvhNode>,
    /// Instances in TLAS leaf order.
    pub instances: Vec<GpuInstance>,
    /// Analytic spheres.
    pub spheres: Vec<GpuSphere>,
    /// Materials.
    pub materials: Vec<GpuMaterial>,
    /// NEE lights.
    pub lights: Vec<GpuLight>,
    /// Alias table, pdf and CDF over `lights`.
    pub light_table: Vec<GpuAliasEntry>,
    /// Texel words of all textures.
    pub texels: Vec<u32>,
    /// Texture records into `texels`.
    pub textures: Vec<GpuTextureRecord>,
    /// Camera, environment, sun and counts.
    pub params: GpuSceneParams,
    /// Features to specialise shaders for.
    pub features: SceneFeatures,
    blas_roots: Vec<u32>,
    triangle_base: Vec<u32>,
}

impl GpuScene {
    /// Packs a validated scene with its BVH (built from that scene).
    pub fn new(scene: &Scene, bvh: &Bvh) -> Self {
        let geo = geometry::pack(scene, bvh);
        let (texels, textures) = params::textures(scene);
        let mut out = Self {
            vertices: geo.vertices,
            indices: geo.indices,
            triangles: geo.triangles,
            blas_nodes: geo.blas_nodes,
            spheres: geo.spheres,
            materials: params::materials(scene),
            texels,
            textures,
            features: scene.features(),
            blas_roots: geo.blas_roots,
            triangle_base: geo.triangle_base,
            ..Default::default()
        };
        out.update_top_level(scene, bvh);
        out
    }

    /// Re-packs what depends on instance placement (TLAS, instances,
    /// world-space emissive triangles) and the camera, after
    /// [`Bvh::rebuild_top_level`].
    pub fn update_top_level(&mut self, scene: &Scene, bvh: &Bvh) {
        self.tlas_nodes = bvh.tlas.nodes.clone();
        let mut gpu_of_instance = vec![u32::MAX; scene.instances.len()];
        self.instances = bvh
            .tlas
            .order
            .iter()
            .enumerate()
            .map(|(slot, &e)| {
                let inst = &bvh.instances[e as usize];
                let (material, kind, scene_instance) = match inst.source {
                    InstanceSource::Mesh(i) => {
                        gpu_of_instance[i as usize] = slot as u32;
                        (scene.instance_material(i as usize), 0, i)
                    }
                    InstanceSource::Spheres => (u32::MAX, 1, u32::MAX),
                };
                GpuInstance {
                    object_to_world: rows(&inst.object_to_world),
                    world_to_object: rows(&inst.world_to_object),
                    blas_root: self.blas_roots[inst.blas as usize],
                    material,
                    kind,
                    scene_instance,
                }
            })
            .collect();
        let mut gpu_of_sphere = vec![u32::MAX; scene.spheres.len()];
        for (slot, s) in self.spheres.iter().enumerate() {
            gpu_of_sphere[s.scene_sphere as usize] = slot as u32;
        }
        let inverse_orders: Vec<Vec<u32>> = bvh
            .blases
            .iter()
            .take(scene.meshes.len())
            .enumerate()
            .map(|(m, b)| {
                let emissive = scene.instances.iter().enumerate().any(|(i, inst)| {
                    inst.mesh as usize == m
                        && scene.materials[scene.instance_material(i) as usize].is_emissive()
                });
                let mut inv = vec![0; if emissive { b.order.len() } else { 0 }];
                if emissive {
                    for (pos, &t) in b.order.iter().enumerate() {
                        inv[t as usize] = pos as u32;
                    }
                }
                inv
            })
            .collect();
        let triangle = |mesh: u32, t: u32| {
            self.triangle_base[mesh as usize] + inverse_orders[mesh as usize][t as usize]
        };
        let dist = LightDistribution::build(scene);
        let (lights, table) = params::lights(
            scene,
            &dist,
            &params::LightRemap {
                instance: &gpu_of_instance,
                triangle: &triangle,
                sphere: &gpu_of_sphere,
            },
        );
        self.lights = lights;
        self.light_table = table;
        self.params = GpuSceneParams {
            camera: params::camera(&scene.camera),
            environment: params::environment(&scene.environment),
            sun: params::sun(scene.sun.as_ref()),
            counts0: [
                (self.indices.len() / 3) as u32,
                self.instances.len() as u32,
                self.spheres.len() as u32,
                self.lights.len() as u32,
            ],
            counts1: [
                self.materials.len() as u32,
                self.textures.len() as u32,
                self.tlas_nodes.len() as u32,
                self.blas_nodes.len() as u32,
            ],
            light: [dist.total_power(), 0.0, 0.0, 0.0],
        };
    }

    /// Bytes of vertices and indices.
    pub fn geometry_bytes(&self) -> usize {
        self.vertices.len() * size_of::<GpuVertex>()
            + self.indices.len() * 4
            + self.triangles.len() * size_of::<GpuTriangle>()
            + self.spheres.len() * size_of::<GpuSphere>()
    }

    /// Bytes of both BVH levels and the instances.
    pub fn bvh_bytes(&self) -> usize {
        (self.blas_nodes.len() + self.tlas_nodes.len()) * size_of::<BvhNode>()
            + self.instances.len() * size_of::<GpuInstance>()
    }

    /// Bytes of every buffer, textures and lights included.
    pub fn total_bytes(&self) -> usize {
        self.geometry_bytes()
            + self.bvh_bytes()
            + self.materials.len() * size_of::<GpuMaterial>()
            + self.lights.len() * size_of::<GpuLight>()
            + self.light_table.len() * size_of::<GpuAliasEntry>()
            + self.texels.len() * 4
            + self.textures.len() * size_of::<GpuTextureRecord>()
            + size_of::<GpuSceneParams>()
    }

    /// Geometry plus BVH bytes per stored (unique, pre-instancing)
    /// triangle; 0 for a scene without triangles.
    pub fn bytes_per_triangle(&self) -> f64 {
        let tris = self.indices.len() / 3;
        if tris == 0 {
            0.0
        } else {
            (self.geometry_bytes() + self.bvh_bytes()) as f64 / tris as f64
        }
    }
}

/// Rows of the 3x4 matrix of an affine transform.
fn rows(m: &Affine3A) -> [[f32; 4]; 3] {
    let c = m.to_cols_array_2d();
    std::array::from_fn(|r| [c[0][r], c[1][r], c[2][r], c[3][r]])
}
