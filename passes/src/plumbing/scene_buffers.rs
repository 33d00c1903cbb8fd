//! The scene on the GPU: one storage buffer per array of a packed [`GpuScene`], imported into each
//! frame's graph and bound by the names the shaders declare in `shaders/common/scene.glsl`.

use bytemuck::Pod;
use lucid_engine::graph::{Access, BufferHandle, ComputePass, RenderGraph};
use lucid_engine::memory::Buffer;
use lucid_engine::scene::gpu::{BvhLayout, GpuScene};
use lucid_engine::scene::SceneFeatures;
use lucid_engine::shader::{SpecValue, Specialization};
use lucid_engine::{Context, Result};
use std::sync::Arc;

/// The names of the scene buffers in the shaders, in [`SceneBuffers::buffers`] order.
const NAMES: [&str; 14] = [
    "b_vertices",
    "b_blas",
    "b_tlas",
    "b_instances",
    "b_spheres",
    "b_materials",
    "b_lights",
    "b_light_table",
    "b_texels",
    "b_textures",
    "b_scene",
    "b_triangle_ids",
    "b_triangles",
    "b_vertex_attributes",
];

/// Slots in [`NAMES`] (and [`SceneBuffers::buffers`]) of the buffers replaced after the upload.
const TLAS: usize = 2;
const INSTANCES: usize = 3;
const MATERIALS: usize = 5;
const LIGHTS: usize = 6;
const LIGHT_TABLE: usize = 7;
const TEXTURES: usize = 9;
const PARAMS: usize = 10;

/// Device-local copies of a packed scene.
pub struct SceneBuffers {
    buffers: [Arc<Buffer>; 14],
    /// New contents of top-level buffers (by index), written in place by each frame's graph
    /// until a frame with them is submitted ([`SceneBuffers::submitted`]).
    pending: Vec<(usize, Arc<Vec<u8>>)>,
    /// The features the scene uses (drive shader specialization).
    pub features: SceneFeatures,
}

fn upload<T: Pod>(ctx: &Context, name: &str, data: &[T]) -> Result<Arc<Buffer>> {
    upload_bytes(ctx, name, bytemuck::cast_slice(data))
}

fn upload_bytes(ctx: &Context, name: &str, data: &[u8]) -> Result<Arc<Buffer>> {
    Buffer::with_data(
        ctx,
        name,
        "scene",
        ash::vk::BufferUsageFlags::STORAGE_BUFFER,
        data,
    )
    .map(Arc::new)
}

impl SceneBuffers {
    /// Uploads every array of `gpu`, and the per-triangle `[material, instance]` ids of the
    /// flattened static geometry (see `lucid_engine::scene::gpu::pack_flat`).
    pub fn upload(ctx: &Context, gpu: &GpuScene, triangle_ids: &[[u32; 2]]) -> Result<Self> {
        Ok(Self {
            buffers: [
                upload(ctx, NAMES[0], &gpu.vertices)?,
                upload(ctx, NAMES[1], gpu.blas_nodes.bytes())?,
                upload(ctx, NAMES[2], gpu.tlas_nodes.bytes())?,
                upload(ctx, NAMES[3], &gpu.instances)?,
                upload(ctx, NAMES[4], &gpu.spheres)?,
                upload(ctx, NAMES[5], &gpu.materials)?,
                upload(ctx, NAMES[6], &gpu.lights)?,
                upload(ctx, NAMES[7], &gpu.light_table)?,
                upload(ctx, NAMES[8], &gpu.texels)?,
                upload(ctx, NAMES[9], &gpu.textures)?,
                upload(ctx, NAMES[10], std::slice::from_ref(&gpu.params))?,
                upload(ctx, NAMES[11], triangle_ids)?,
                upload(ctx, NAMES[12], &gpu.triangles)?,
                upload(ctx, NAMES[13], &gpu.vertex_attributes)?,
            ],
            pending: Vec::new(),
            features: gpu.features,
        })
    }

    /// Replaces what moving instances changes (TLAS, instances, lights, params). Arrays whose size
    /// stays the same (every move of an instance) are written in place by the next frame's graph,
    /// after the frames in flight on the queue: no upload waits for the GPU. Others get new
    /// buffers at once (frames in flight keep the old ones alive until they finish).
    pub fn update_top_level(&mut self, ctx: &Context, gpu: &GpuScene) -> Result<()> {
        let arrays: [(usize, &[u8]); 5] = [
            (TLAS, gpu.tlas_nodes.bytes()),
            (INSTANCES, bytemuck::cast_slice(&gpu.instances)),
            (LIGHTS, bytemuck::cast_slice(&gpu.lights)),
            (LIGHT_TABLE, bytemuck::cast_slice(&gpu.light_table)),
            (PARAMS, bytemuck::bytes_of(&gpu.params)),
        ];
        for (i, data) in arrays {
            self.pending.retain(|(j, _)| *j != i);
            let in_place = !data.is_empty()
                && data.len() % 4 == 0
                && data.len() as u64 == self.buffers[i].size();
            if in_place {
                self.pending.push((i, Arc::new(data.to_vec())));
            } else {
                self.buffers[i] = upload_bytes(ctx, NAMES[i], data)?;
            }
        }
        Ok(())
    }

    /// Replaces the materials, their texture records (and params) after a material edit.
    pub fn update_materials(&mut self, ctx: &Context, gpu: &GpuScene) -> Result<()> {
        self.buffers[MATERIALS] = upload(ctx, NAMES[MATERIALS], &gpu.materials)?;
        self.buffers[TEXTURES] = upload(ctx, NAMES[TEXTURES], &gpu.textures)?;
        self.update_top_level(ctx, gpu)
    }

    /// Imports the buffers into a frame's graph, with a pass writing the pending top-level
    /// contents first.
    pub fn import(&self, g: &mut RenderGraph) -> SceneHandles {
        let mut handles =
            std::array::from_fn(|i| g.import_buffer(NAMES[i], self.buffers[i].clone()));
        if !self.pending.is_empty() {
            let mut p = g.add_pass("scene.update_top_level");
            let writes: Vec<(BufferHandle, Arc<Vec<u8>>)> = self
                .pending
                .iter()
                .map(|(i, data)| {
                    handles[*i] = p.write(handles[*i], Access::TransferWrite);
                    (handles[*i], data.clone())
                })
                .collect();
            p.execute(move |ctx| {
                writes
                    .iter()
                    .try_for_each(|(buffer, data)| ctx.update_buffer(*buffer, data))
            });
        }
        SceneHandles { handles }
    }

    /// A frame with the pending top-level contents was submitted: later frames need not write
    /// them again.
    pub fn submitted(&mut self) {
        self.pending.clear();
    }

    /// Bytes of scene data on the GPU.
    pub fn bytes(&self) -> u64 {
        self.buffers.iter().map(|b| b.size()).sum()
    }
}

/// The scene buffers of one frame's graph.
#[derive(Clone, Copy, Debug)]
pub struct SceneHandles {
    handles: [BufferHandle; 14],
}

impl SceneHandles {
    /// Reads every scene buffer in `pass`, bound by its shader name.
    pub fn read(&self, pass: &mut ComputePass<'_>) {
        for (name, h) in NAMES.iter().zip(self.handles) {
            pass.read(name, h);
        }
    }
}

/// The specialization constants that compile out what a scene lacks: its features, the
/// traversal's constants ([`traversal_specialization`]), and `RESAMPLE_LIGHTS`, off where the
/// lights are one flat emitter ([`GpuScene::lights_form_one_flat_emitter`]).
pub fn specialization(gpu: &GpuScene) -> Specialization {
    let used = |name: &str| {
        gpu.features
            .specialization_constants()
            .iter()
            .find(|(n, _)| *n == name)
            .is_some_and(|(_, v)| *v)
    };
    [
        "HAS_CONDUCTOR",
        "HAS_DIELECTRIC",
        "HAS_DIELECTRIC_ROUGH",
        "HAS_METAL_ROUGH",
        "HAS_SUN",
        "HAS_DELTA_LIGHTS",
        "HAS_ENVIRONMENT",
        "HAS_ENVIRONMENT_MAP",
        "HAS_TEXTURES",
        "HAS_VERTEX_COLORS",
        "HAS_NORMAL_MAPS",
        "HAS_EMISSIVE_TEXTURES",
        "HAS_OCCLUSION",
        "HAS_TEXTURE_TRANSFORMS",
    ]
    .into_iter()
    .fold(traversal_specialization(gpu), |spec, name| {
        spec.set(name, used(name))
    })
    .set("RESAMPLE_LIGHTS", !gpu.lights_form_one_flat_emitter())
}

/// The most instances rays walk one after the other instead of through the top level
/// (`FEW_INSTANCES` in `shaders/common/traverse.glsl`).
pub const MAX_FEW_INSTANCES: usize = 4;

/// The constants of `shaders/common/traverse.glsl` alone, for passes that only trace (see
/// [`crate::debug::ray_query`]): `HAS_SPHERES`, `HAS_ALPHA_TEST` (cut-out surfaces let rays
/// through), `SINGLE_INSTANCE` when the packing is one triangle instance
/// ([`GpuScene::single_instance`]; the traversal then skips the top level), `FEW_INSTANCES` when
/// there are more but at most [`MAX_FEW_INSTANCES`] (each one's BLAS walked in turn, no top level
/// either), and `WIDE_BVH` for the layout of the nodes ([`GpuScene::layout`]).
pub fn traversal_specialization(gpu: &GpuScene) -> Specialization {
    let (blas_words, triangle_words) = workgroup_scene_words(gpu);
    Specialization::new()
        .set("HAS_SPHERES", gpu.features.spheres)
        .set("HAS_ALPHA_TEST", gpu.features.alpha_test)
        .set("SINGLE_INSTANCE", gpu.single_instance())
        .set(
            "FEW_INSTANCES",
            !gpu.single_instance() && gpu.instances.len() <= MAX_FEW_INSTANCES,
        )
        .set("WIDE_BVH", gpu.layout() == BvhLayout::Wide)
        .set("WORKGROUP_BLAS_WORDS", blas_words)
        .set("WORKGROUP_TRIANGLE_WORDS", triangle_words)
}

/// The most bytes of BLAS nodes and triangle records that the tracing kernels copy into each
/// workgroup's memory (`shaders/common/workgroup_scene.glsl`): with the kernels' own arrays it
/// stays under the 16 KiB every Vulkan device offers, and the path tracer's workgroups on an H200
/// stay limited by their registers, not by workgroup memory.
pub const MAX_WORKGROUP_SCENE_BYTES: usize = 8192;

/// The fewest triangles for which the copy pays: below it a walk is a step or two (`caustics`,
/// 4 triangles and a sphere: BDPT's camera pass 3% slower on an H200 with the copy,
/// `bench/README.md`).
pub const MIN_WORKGROUP_SCENE_TRIANGLES: usize = 16;

/// The 16-byte words of BLAS nodes and of triangle records that the tracing kernels copy into
/// workgroup memory and walk there (the `WORKGROUP_BLAS_WORDS` and `WORKGROUP_TRIANGLE_WORDS`
/// constants): all of both for a single instance (in either layout; the Cornell box: 10% off its
/// path tracer on an H200 in the binary one) of at least [`MIN_WORKGROUP_SCENE_TRIANGLES`]
/// triangles within [`MAX_WORKGROUP_SCENE_BYTES`], else none (0, 0).
pub fn workgroup_scene_words(gpu: &GpuScene) -> (u32, u32) {
    let nodes = gpu.blas_nodes.bytes().len();
    let triangles = std::mem::size_of_val(gpu.triangles.as_slice());
    let fits = gpu.single_instance()
        && gpu.triangles.len() >= MIN_WORKGROUP_SCENE_TRIANGLES
        && nodes + triangles <= MAX_WORKGROUP_SCENE_BYTES;
    let words = |bytes: usize| (bytes / std::mem::size_of::<[u32; 4]>()) as u32;
    if fits {
        (words(nodes), words(triangles))
    } else {
        (0, 0)
    }
}

/// Whether `spec` (made by [`traversal_specialization`]) has the tracing kernels walk the scene in
/// workgroup memory: the path tracer then runs its shader that declares it.
pub fn scene_in_workgroup(spec: &Specialization) -> bool {
    spec.get("WORKGROUP_BLAS_WORDS")
        .is_some_and(|words| words != SpecValue::from(0u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_replaced_slots_name_their_buffers() {
        let slots = [
            (TLAS, "b_tlas"),
            (INSTANCES, "b_instances"),
            (MATERIALS, "b_materials"),
            (LIGHTS, "b_lights"),
            (LIGHT_TABLE, "b_light_table"),
            (TEXTURES, "b_textures"),
            (PARAMS, "b_scene"),
        ];
        for (slot, name) in slots {
            assert_eq!(NAMES[slot], name);
        }
    }

    #[test]
    fn only_small_single_instances_go_to_workgroup_memory() {
        use lucid_engine::scene::gpu::pack_flat;
        use lucid_engine::scene::{builtin, Bvh, FlatScene};
        let words = |name: &str, layout: BvhLayout| {
            let options = builtin::BuildOptions { detail: 0.01 };
            let scene = builtin::build_with(name, &options).unwrap();
            let flat = FlatScene::new(&scene, &vec![false; scene.instances.len()]);
            let (gpu, _) = pack_flat(&flat, &scene, &Bvh::build(&flat.scene), layout);
            let spec = traversal_specialization(&gpu);
            let (blas, triangles) = workgroup_scene_words(&gpu);
            assert_eq!(spec.get("WORKGROUP_BLAS_WORDS"), Some(blas.into()));
            assert_eq!(spec.get("WORKGROUP_TRIANGLE_WORDS"), Some(triangles.into()));
            assert_eq!(scene_in_workgroup(&spec), blas > 0);
            (gpu, blas, triangles)
        };
        let (cornell, blas, triangles) = words("cornell-box", BvhLayout::Binary);
        assert_eq!(blas as usize * 16, cornell.blas_nodes.bytes().len());
        assert_eq!(triangles as usize, 3 * cornell.triangles.len());
        assert!(16 * (blas + triangles) as usize <= MAX_WORKGROUP_SCENE_BYTES);
        let (wide, blas, _) = words("cornell-box", BvhLayout::Wide);
        assert_eq!(
            blas as usize * 16,
            wide.blas_nodes.bytes().len(),
            "wide nodes too"
        );
        assert_eq!(
            words("caustics", BvhLayout::Binary).1,
            0,
            "too few triangles to pay"
        );
        let (teapot, _, triangles) = words("cornell-teapot", BvhLayout::Binary);
        assert!(teapot.single_instance());
        assert_eq!(triangles, 0, "too large");
    }

    #[test]
    fn light_resampling_is_off_only_for_one_flat_emitter() {
        use lucid_engine::scene::{builtin, Bvh};
        let resample = |name: &str| {
            let options = builtin::BuildOptions { detail: 0.01 };
            let scene = builtin::build_with(name, &options).unwrap();
            let gpu = GpuScene::new(&scene, &Bvh::build(&scene));
            specialization(&gpu).get("RESAMPLE_LIGHTS")
        };
        assert_eq!(resample("cornell-box"), Some(false.into()));
        assert_eq!(resample("caustics"), Some(false.into()));
        assert_eq!(resample("classroom"), Some(true.into()));
    }
}
