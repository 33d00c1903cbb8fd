//! The packed, GPU-ready form of a scene: plain `Vec<T: Pod>` arrays that
//! upload 1:1 into storage buffers.
//!
//! Buffers and how they reference each other:
//! - `vertices` ([`GpuVertex`], 20 B) and `indices` (3 × `u32` per
//!   triangle, absolute vertex indices); `vertex_attributes` ([`GpuVertexAttributes`], 16 B per
//!   vertex: colour, alpha, tangent) only when a mesh has vertex colours or tangents. Each mesh's
//!   triangles are stored in its packed BLAS's order, so a BLAS leaf names a global triangle
//!   range directly.
//! - `blas_nodes` / `tlas_nodes` ([`GpuNodes`], in one of two [`BvhLayout`]s): binary
//!   ([`GpuBvhNode`], 64 B, see [`bvh_pack`]: interior nodes holding both children's boxes and
//!   child words) or compressed 8-wide ([`wide::WideNode`], 80 B, see [`wide`]); all
//!   BLASes concatenated with absolute node and triangle indices; TLAS
//!   leaves index `instances`, which are stored in the packed TLAS's order.
//! - `instances` ([`GpuInstance`]): transforms, BLAS root, material.
//! - `spheres` ([`GpuSphere`]) in the packed sphere BLAS's order.
//! - `materials`, `textures` (one record per texture a material uses: where its texels lie in
//!   the flat `texels` word buffer, its coordinate transform and wrap modes).
//! - `lights` + `light_table`: the NEE light list with its alias table / CDF
//!   (power and uniform selection, see [`crate::scene::LightDistribution`]), then an environment
//!   map's cells ([`crate::scene::EnvironmentDistribution`]).
//! - `params`: camera, environment, sun, counts.

pub mod bvh_pack;
mod encode;
mod flat;
mod flat_emitter;
mod geometry;
mod layout;
#[cfg(feature = "clap")]
mod layout_value_enum;
mod nodes;
mod params;
pub mod wide;

pub use bvh_pack::GpuBvhNode;
pub use encode::{decode_normal, encode_color, encode_normal, encode_uv};
pub use flat::{apply_flattening, pack_flat, INSTANCE_FLATTENED};
pub use layout::material_flags;
pub use layout::{
    light_kind, material_kind, texture_format, GpuAliasEntry, GpuCamera, GpuEnvironment,
    GpuInstance, GpuLight, GpuMaterial, GpuSceneParams, GpuSphere, GpuSun, GpuTextureRecord,
    GpuTriangle, GpuVertex, GpuVertexAttributes,
};
pub use nodes::{BvhLayout, GpuNodes, PackedTree};
pub use params::camera;

use std::mem::size_of;

use glam::Affine3A;

use super::{Environment, EnvironmentDistribution, LightDistribution, Scene, SceneFeatures};
use crate::scene::{Bvh, InstanceSource};

/// `GpuInstance::kind` of a mesh instance.
pub const INSTANCE_TRIANGLES: u32 = 0;

/// `GpuInstance::kind` of the instance of all spheres.
pub const INSTANCE_SPHERES: u32 = 1;

/// The most spheres [`GpuScene::single_instance`] lets rays test one by one beside its triangle
/// instance, rather than through their BLAS.
pub const MAX_LOOSE_SPHERES: usize = 8;

/// Everything the GPU passes need, CPU side.
#[derive(Clone, Debug, Default)]
pub struct GpuScene {
    /// Mesh vertices.
    pub vertices: Vec<GpuVertex>,
    /// Vertex colours, alphas and tangents, one per vertex, when some mesh has colours or
    /// tangents; else empty (and `HAS_VERTEX_COLORS` and `HAS_NORMAL_MAPS` off).
    pub vertex_attributes: Vec<GpuVertexAttributes>,
    /// Triangles: what ray intersection reads (first vertex and edges) and their vertex indices.
    pub triangles: Vec<GpuTriangle>,
    /// All bottom-level nodes.
    pub blas_nodes: GpuNodes,
    /// Top-level nodes (in the layout of `blas_nodes`).
    pub tlas_nodes: GpuNodes,
    /// Root of the TLAS (see [`PackedTree::root`]; `u32::MAX` without instances).
    pub tlas_root: u32,
    /// Instances in the packed TLAS's order.
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
    /// The top level's box, grown a little ([`GpuSceneParams::bounds_min`]).
    bounds: [[f32; 4]; 2],
    /// The environment map's texture record (`u32::MAX` without a map).
    environment_record: u32,
    /// The environment map's sampling distribution (empty without a map); its alias table follows
    /// the lights' in `light_table`.
    environment_distribution: EnvironmentDistribution,
    /// Root of each BLAS.
    blas_roots: Vec<u32>,
    /// Per BLAS, the source primitive of each packed primitive.
    blas_orders: Vec<Vec<u32>>,
    /// Nodes on the longest root-to-leaf path of any BLAS and of the TLAS.
    depths: BvhDepths,
    triangle_base: Vec<u32>,
}

/// The longest root-to-leaf paths of a packed scene's trees, in nodes (the GPU traversal's stacks
/// hold at most one entry per level, binary or wide).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BvhDepths {
    /// The deepest bottom level.
    pub blas: u32,
    /// The top level.
    pub tlas: u32,
}

impl GpuScene {
    /// Packs a validated scene with its BVH (built from that scene) in the default layout.
    pub fn new(scene: &Scene, bvh: &Bvh) -> Self {
        Self::with_layout(scene, bvh, BvhLayout::default())
    }

    /// A lower bound of the bytes packing `scene` takes on the device, from the triangle and vertex
    /// counts of the meshes its instances use (each such mesh's triangle records and
    /// vertices, once; no BVH, instances, textures or lights), so known before the BVH is built.
    pub fn least_bytes(scene: &Scene) -> u64 {
        let mut used = vec![false; scene.meshes.len()];
        for instance in &scene.instances {
            if let Some(u) = used.get_mut(instance.mesh as usize) {
                *u = true;
            }
        }
        scene
            .meshes
            .iter()
            .zip(used)
            .filter(|(_, used)| *used)
            .map(|(m, _)| {
                let triangles = m.indices.len() as u64;
                let per_triangle = size_of::<GpuTriangle>() as u64;
                triangles * per_triangle + m.positions.len() as u64 * size_of::<GpuVertex>() as u64
            })
            .sum()
    }

    /// Packs a validated scene with its BVH (built from that scene) in `layout`.
    pub fn with_layout(scene: &Scene, bvh: &Bvh, layout: BvhLayout) -> Self {
        let mut out = Self::without_top_level(scene, bvh, layout);
        out.update_top_level(scene, bvh);
        out
    }

    /// Packs what does not depend on instance placement: geometry, bottom levels in `layout`,
    /// materials, textures and features. The instances, lights and params are left empty.
    fn without_top_level(scene: &Scene, bvh: &Bvh, layout: BvhLayout) -> Self {
        let geo = geometry::pack(scene, bvh, layout);
        let (texels, images) = params::textures(scene);
        let (materials, textures, environment_record) = params::materials(scene, &images);
        let environment_distribution = match scene.environment {
            Environment::Map { texture } => {
                EnvironmentDistribution::new(&scene.textures[texture as usize])
            }
            _ => EnvironmentDistribution::default(),
        };
        Self {
            environment_record,
            environment_distribution,
            vertices: geo.vertices,
            vertex_attributes: geo.vertex_attributes,
            triangles: geo.triangles,
            blas_nodes: geo.blas_nodes,
            tlas_nodes: GpuNodes::new(layout),
            spheres: geo.spheres,
            materials,
            texels,
            textures,
            images,
            features: scene.features(),
            blas_roots: geo.blas_roots,
            blas_orders: geo.blas_orders,
            depths: BvhDepths {
                blas: geo.blas_depth,
                tlas: 0,
            },
            triangle_base: geo.triangle_base,
            ..Default::default()
        }
    }

    /// Re-packs the materials of `scene` and their texture records (after a material edit); the
    /// lights that depend on them are re-packed with the top level ([`Self::update_top_level`] or
    /// [`apply_flattening`]).
    pub fn update_materials(&mut self, scene: &Scene) {
        (self.materials, self.textures, self.environment_record) =
            params::materials(scene, &self.images);
    }

    /// Re-packs what depends on instance placement (TLAS, instances,
    /// world-space emissive triangles) and the camera, after
    /// [`Bvh::rebuild_top_level`].
    pub fn update_top_level(&mut self, scene: &Scene, bvh: &Bvh) {
        let gpu_of_instance = self.place_instances(scene, bvh);
        let inverse_orders = emitter_inverse_orders(scene, &self.blas_orders, |i| {
            scene.instances[i].mesh as usize
        });
        let triangle = |instance: u32, t: u32| {
            let mesh = scene.instances[instance as usize].mesh as usize;
            self.triangle_base[mesh] + inverse_orders[mesh][t as usize]
        };
        let (lights, table, light) = self.pack_lights(scene, &gpu_of_instance, &triangle);
        self.set_lights(scene, lights, table, light);
    }

    /// Packs the TLAS and the instances of `scene` (in the packed TLAS's order); returns the GPU
    /// instance slot of each scene instance.
    fn place_instances(&mut self, scene: &Scene, bvh: &Bvh) -> Vec<u32> {
        self.tlas_nodes = GpuNodes::new(self.layout());
        let packed = self
            .tlas_nodes
            .pack_tree(&bvh.tlas.nodes, &bvh.tlas.order, 0);
        self.tlas_root = packed.root;
        self.depths.tlas = packed.depth;
        self.bounds = bvh
            .tlas
            .nodes
            .first()
            .map_or([[0.0; 4]; 2], |root| grown(root.bounds()));
        let mut gpu_of_instance = vec![u32::MAX; scene.instances.len()];
        self.instances = packed
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
        // The map's table starts right after the lights' (one entry per light, zero where none
        // has power), at `counts0.w`.
        self.light_table
            .resize(self.lights.len(), GpuAliasEntry::default());
        let offset = self.light_table.len() as u32;
        self.light_table.extend(params::environment_table(
            &self.environment_distribution,
            offset,
        ));
        let cells = [
            self.environment_distribution.width,
            self.environment_distribution.height,
        ];
        self.params = GpuSceneParams {
            camera: params::camera(&scene.camera),
            environment: params::environment(&scene.environment, self.environment_record, cells),
            sun: params::sun(scene.sun.as_ref()),
            counts0: [
                self.triangles.len() as u32,
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
            bounds_min: self.bounds[0],
            bounds_max: self.bounds[1],
        };
    }

    /// The layout the BVH nodes are packed in.
    pub fn layout(&self) -> BvhLayout {
        self.blas_nodes.layout()
    }

    /// The longest root-to-leaf paths of the packed trees.
    pub fn bvh_depths(&self) -> BvhDepths {
        self.depths
    }

    /// An error naming the tree when a packed tree is deeper than the GPU walks of its layout can
    /// stack for ([`BvhLayout::max_depths`]): they would skip subtrees.
    pub fn check_depths(&self) -> Result<(), String> {
        let max = self.layout().max_depths();
        for (level, depth, most) in [
            ("bottom", self.depths.blas, max.blas),
            ("top", self.depths.tlas, max.tlas),
        ] {
            if depth > most {
                return Err(format!(
                    "a {level}-level BVH is {depth} nodes deep; the GPU traversal of the {} layout \
                     handles at most {most}",
                    self.layout()
                ));
            }
        }
        Ok(())
    }

    /// Whether the packed scene is exactly one triangle instance, alone or beside the instance of
    /// at most [`MAX_LOOSE_SPHERES`] spheres: rays may then skip the top level, walk that
    /// instance's BLAS directly and test the spheres one by one (the `SINGLE_INSTANCE`
    /// specialization constant). A fully flattened static scene is one.
    pub fn single_instance(&self) -> bool {
        let triangle_instances = self
            .instances
            .iter()
            .filter(|i| i.kind != INSTANCE_SPHERES)
            .count();
        triangle_instances == 1
            && (self.instances.len() == 1 || self.spheres.len() <= MAX_LOOSE_SPHERES)
    }

    /// Bytes of vertices, triangles and spheres.
    pub fn geometry_bytes(&self) -> usize {
        self.vertices.len() * size_of::<GpuVertex>()
            + self.vertex_attributes.len() * size_of::<GpuVertexAttributes>()
            + self.triangles.len() * size_of::<GpuTriangle>()
            + self.spheres.len() * size_of::<GpuSphere>()
    }

    /// Bytes of both BVH levels and the instances.
    pub fn bvh_bytes(&self) -> usize {
        self.blas_nodes.bytes().len()
            + self.tlas_nodes.bytes().len()
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
        let tris = self.triangles.len();
        if tris == 0 {
            0.0
        } else {
            (self.geometry_bytes() + self.bvh_bytes()) as f64 / tris as f64
        }
    }
}

/// Per packed BLAS (`orders`: the source triangle of each packed triangle): the packed position of
/// each triangle when the BLAS holds an emitter of `scene` (whose instance `i` lies in BLAS
/// `blas_of(i)`), else empty. Lights use it to find their GPU triangles.
fn emitter_inverse_orders(
    scene: &Scene,
    orders: &[Vec<u32>],
    blas_of: impl Fn(usize) -> usize,
) -> Vec<Vec<u32>> {
    let mut lit = vec![false; orders.len()];
    for i in 0..scene.instances.len() {
        if scene.materials[scene.instance_material(i) as usize].is_emissive() {
            lit[blas_of(i)] = true;
        }
    }
    lit.iter()
        .zip(orders)
        .map(|(&lit, order)| {
            if lit {
                inverse_order(order)
            } else {
                Vec::new()
            }
        })
        .collect()
}

/// Position of each triangle in a packed order (`order` maps position to triangle).
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

/// `bounds` grown by a thousandth of its diagonal and a millimetre, so that a ray started on the
/// grown box starts off every surface, as `[min, max]` with w 0.
fn grown(bounds: crate::bvh::Aabb) -> [[f32; 4]; 2] {
    let margin = glam::Vec3::splat(1e-3 * (bounds.max - bounds.min).length() + 1e-3);
    [
        (bounds.min - margin).extend(0.0).to_array(),
        (bounds.max + margin).extend(0.0).to_array(),
    ]
}
