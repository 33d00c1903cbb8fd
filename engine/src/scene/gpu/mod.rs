//! The packed, GPU-ready form of a scene: plain `Vec<T: Pod>` arrays that
//! upload 1:1 into storage buffers.
//!
//! Buffers and how they reference each other:
//! - `vertices` ([`GpuVertex`], 20 B) and `indices` (3 × `u32` per
//!   triangle, absolute vertex indices); `vertex_attributes` ([`GpuVertexAttributes`], 16 B per
//!   vertex: colour, alpha, tangent) only when a mesh has vertex colours or tangents. Each mesh's triangles are stored
//!   in its BLAS leaf order, so a BLAS leaf `(first, count)` is directly a
//!   global triangle range.
//! - `blas_nodes` / `tlas_nodes` ([`GpuBvhNode`], 64 B, see [`bvh_pack`]):
//!   interior nodes holding both children's boxes and child words; all
//!   BLASes concatenated with absolute node and triangle indices; TLAS
//!   leaves index `instances`, which are stored in TLAS leaf order.
//! - `instances` ([`GpuInstance`]): transforms, BLAS root, material.
//! - `spheres` ([`GpuSphere`]) in sphere-BLAS leaf order.
//! - `materials`, `textures` (one record per texture a material uses: where its texels lie in
//!   the flat `texels` word buffer, its coordinate transform and wrap modes).
//! - `lights` + `light_table`: the NEE light list with its alias table / CDF
//!   (power and uniform selection, see [`crate::scene::LightDistribution`]).
//! - `params`: camera, environment, sun, counts.

pub mod bvh_pack;
mod encode;
mod flat;
mod geometry;
mod layout;
mod params;

pub use bvh_pack::GpuBvhNode;
pub use encode::{decode_normal, encode_color, encode_normal, encode_uv};
pub use flat::{apply_flattening, pack_flat, INSTANCE_FLATTENED};
pub use layout::material_flags;
pub use layout::{
    light_kind, material_kind, texture_format, GpuAliasEntry, GpuCamera, GpuEnvironment,
    GpuInstance, GpuLight, GpuMaterial, GpuSceneParams, GpuSphere, GpuSun, GpuTextureRecord,
    GpuTriangle, GpuVertex, GpuVertexAttributes,
};
pub use params::camera;

use std::mem::size_of;

use glam::Affine3A;

use super::{LightDistribution, Scene, SceneFeatures};
use crate::scene::{Bvh, InstanceSource};

/// `GpuInstance::kind` of a mesh instance.
pub const INSTANCE_TRIANGLES: u32 = 0;

/// `GpuInstance::kind` of the instance of all spheres.
pub const INSTANCE_SPHERES: u32 = 1;

/// Everything the GPU passes need, CPU side.
#[derive(Clone, Debug, Default)]
pub struct GpuScene {
    /// Mesh vertices.
    pub vertices: Vec<GpuVertex>,
    /// Vertex colours, alphas and tangents, one per vertex, when some mesh has colours or
    /// tangents; else empty (and `HAS_VERTEX_COLORS` and `HAS_NORMAL_MAPS` off).
    pub vertex_attributes: Vec<GpuVertexAttributes>,
    /// Triangle vertex indices, three per triangle.
    pub indices: Vec<u32>,
    /// Triangles for ray intersection (first vertex and edges), in the order of `indices`.
    pub triangles: Vec<GpuTriangle>,
    /// All bottom-level nodes.
    pub blas_nodes: Vec<GpuBvhNode>,
    /// Top-level nodes.
    pub tlas_nodes: Vec<GpuBvhNode>,
    /// Root child word of the TLAS ([`bvh_pack::EMPTY`] without instances).
    pub tlas_root: u32,
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
    /// Texture records (one per material texture slot) into `texels`.
    pub textures: Vec<GpuTextureRecord>,
    /// Camera, environment, sun and counts.
    pub params: GpuSceneParams,
    /// Features to specialise shaders for.
    pub features: SceneFeatures,
    /// Where each scene texture's texels lie (identity transform, repeating).
    images: Vec<GpuTextureRecord>,
    /// Root child word of each BLAS.
    blas_roots: Vec<u32>,
    triangle_base: Vec<u32>,
}

impl GpuScene {
    /// Packs a validated scene with its BVH (built from that scene).
    pub fn new(scene: &Scene, bvh: &Bvh) -> Self {
        let mut out = Self::without_top_level(scene, bvh);
        out.update_top_level(scene, bvh);
        out
    }

    /// Packs what does not depend on instance placement: geometry, bottom levels, materials,
    /// textures and features. The instances, lights and params are left empty.
    fn without_top_level(scene: &Scene, bvh: &Bvh) -> Self {
        let geo = geometry::pack(scene, bvh);
        let (texels, images) = params::textures(scene);
        let (materials, textures) = params::materials(scene, &images);
        Self {
            vertices: geo.vertices,
            vertex_attributes: geo.vertex_attributes,
            indices: geo.indices,
            triangles: geo.triangles,
            blas_nodes: geo.blas_nodes,
            spheres: geo.spheres,
            materials,
            texels,
            textures,
            images,
            features: scene.features(),
            blas_roots: geo.blas_roots,
            triangle_base: geo.triangle_base,
            ..Default::default()
        }
    }

    /// Re-packs the materials of `scene` and their texture records (after a material edit); the
    /// lights that depend on them are re-packed with the top level ([`Self::update_top_level`] or
    /// [`apply_flattening`]).
    pub fn update_materials(&mut self, scene: &Scene) {
        (self.materials, self.textures) = params::materials(scene, &self.images);
    }

    /// Re-packs what depends on instance placement (TLAS, instances,
    /// world-space emissive triangles) and the camera, after
    /// [`Bvh::rebuild_top_level`].
    pub fn update_top_level(&mut self, scene: &Scene, bvh: &Bvh) {
        let gpu_of_instance = self.place_instances(scene, bvh);
        let inverse_orders =
            emitter_inverse_orders(scene, bvh, |i| scene.instances[i].mesh as usize);
        let triangle = |instance: u32, t: u32| {
            let mesh = scene.instances[instance as usize].mesh as usize;
            self.triangle_base[mesh] + inverse_orders[mesh][t as usize]
        };
        let (lights, table, light) = self.pack_lights(scene, &gpu_of_instance, &triangle);
        self.set_lights(scene, lights, table, light);
    }

    /// Packs the TLAS and the instances of `scene` (in TLAS leaf order); returns the GPU instance
    /// slot of each scene instance.
    fn place_instances(&mut self, scene: &Scene, bvh: &Bvh) -> Vec<u32> {
        self.tlas_nodes.clear();
        self.tlas_root = bvh_pack::pack_tree(&bvh.tlas.nodes, 0, &mut self.tlas_nodes);
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
                        (scene.instance_material(i as usize), INSTANCE_TRIANGLES, i)
                    }
                    InstanceSource::Spheres => (u32::MAX, INSTANCE_SPHERES, u32::MAX),
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
        gpu_of_instance
    }

    /// The NEE lights of `scene` (whose instances `instance` maps to GPU instance slots and whose
    /// `(instance, triangle)` pairs `triangle` maps to global GPU triangles), their alias table and
    /// total power.
    fn pack_lights(
        &self,
        scene: &Scene,
        instance: &[u32],
        triangle: &dyn Fn(u32, u32) -> u32,
    ) -> (Vec<GpuLight>, Vec<GpuAliasEntry>, [f32; 4]) {
        let mut gpu_of_sphere = vec![u32::MAX; scene.spheres.len()];
        for (slot, s) in self.spheres.iter().enumerate() {
            gpu_of_sphere[s.scene_sphere as usize] = slot as u32;
        }
        let dist = LightDistribution::build(scene);
        let (lights, table) = params::lights(
            scene,
            &dist,
            &params::LightRemap {
                instance,
                triangle,
                sphere: &gpu_of_sphere,
            },
        );
        let light = [
            dist.total_power(),
            dist.selection.uniform,
            dist.selection.power_scale,
            0.0,
        ];
        (lights, table, light)
    }

    /// Stores the lights and packs the params (camera, environment and sun of `scene`, counts,
    /// `light`: total light power and the selection constants, see [`GpuSceneParams::light`]).
    fn set_lights(
        &mut self,
        scene: &Scene,
        lights: Vec<GpuLight>,
        table: Vec<GpuAliasEntry>,
        light: [f32; 4],
    ) {
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
                self.tlas_root,
                self.blas_nodes.len() as u32,
            ],
            light,
        };
    }

    /// Whether the packed scene is exactly one triangle instance (no spheres): rays may then skip
    /// the top level and walk that instance's BLAS directly (the `SINGLE_INSTANCE` specialization
    /// constant). A fully flattened static scene is one.
    pub fn single_instance(&self) -> bool {
        matches!(self.instances.as_slice(), [only] if only.kind != INSTANCE_SPHERES)
    }

    /// Bytes of vertices and indices.
    pub fn geometry_bytes(&self) -> usize {
        self.vertices.len() * size_of::<GpuVertex>()
            + self.vertex_attributes.len() * size_of::<GpuVertexAttributes>()
            + self.indices.len() * 4
            + self.triangles.len() * size_of::<GpuTriangle>()
            + self.spheres.len() * size_of::<GpuSphere>()
    }

    /// Bytes of both BVH levels and the instances.
    pub fn bvh_bytes(&self) -> usize {
        (self.blas_nodes.len() + self.tlas_nodes.len()) * size_of::<GpuBvhNode>()
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

/// Per BLAS of `bvh`: the position of each triangle in its leaf order when the BLAS holds an
/// emitter of `scene` (whose instance `i` lies in BLAS `blas_of(i)`), else empty. Lights use it to
/// find their GPU triangles.
fn emitter_inverse_orders(
    scene: &Scene,
    bvh: &Bvh,
    blas_of: impl Fn(usize) -> usize,
) -> Vec<Vec<u32>> {
    let mut lit = vec![false; bvh.blases.len()];
    for i in 0..scene.instances.len() {
        if scene.materials[scene.instance_material(i) as usize].is_emissive() {
            lit[blas_of(i)] = true;
        }
    }
    lit.iter()
        .zip(&bvh.blases)
        .map(|(&lit, blas)| {
            if lit {
                inverse_order(&blas.order)
            } else {
                Vec::new()
            }
        })
        .collect()
}

/// Position of each triangle in a BLAS leaf order (`order` maps position to triangle).
fn inverse_order(order: &[u32]) -> Vec<u32> {
    let mut inverse = vec![0; order.len()];
    for (position, &t) in order.iter().enumerate() {
        inverse[t as usize] = position as u32;
    }
    inverse
}

/// Rows of the 3x4 matrix of an affine transform.
fn rows(m: &Affine3A) -> [[f32; 4]; 3] {
    let c = m.to_cols_array_2d();
    std::array::from_fn(|r| [c[0][r], c[1][r], c[2][r], c[3][r]])
}
