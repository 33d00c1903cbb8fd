//! Batch ray queries on the GPU (`shaders/ray_query/ray_query.comp`): closest hit and occlusion
//! for a buffer of rays. Tests check the GPU traversal against the CPU BVH with it.

use crate::plumbing::scene_buffers::SceneHandles;
use crate::shaders::ray_query::RAY_QUERY;
use bytemuck::{Pod, Zeroable};
use lucid_engine::graph::{BufferHandle, RenderGraph};
use lucid_engine::shader::Specialization;

/// One query ray (std430 `RayIn`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct QueryRay {
    /// Origin (xyz) and the farthest distance (w).
    pub origin_tmax: [f32; 4],
    /// Direction (xyz), need not be unit length; w unused.
    pub dir: [f32; 4],
}

/// One result (std430 `HitOut`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct QueryHit {
    /// Distance to the closest hit in units of the ray direction, or -1 on a miss.
    pub t: f32,
    /// Scene instance index, or `0x8000_0000 | sphere index`; `u32::MAX` on a miss.
    pub object_id: u32,
    /// 1 when anything lies within `t_max`.
    pub occluded: u32,
    /// The same as the paired walk answers it (`trace_occluded_pair`, which BDPT's camera pass
    /// uses): bit 0 with the ray walked first beside its neighbour (index ^ 1), bit 1 with it
    /// walked second after the neighbour; 3 or 0 where the walks agree with `occluded`.
    pub paired: u32,
}

/// Object id of a sphere in [`QueryHit::object_id`].
pub const SPHERE_BIT: u32 = 0x8000_0000;

/// Adds a pass answering `count` rays from `rays`, specialised with `spec` (see
/// [`crate::plumbing::scene_buffers::traversal_specialization`]); returns the buffer of [`QueryHit`]s.
pub fn add_ray_query(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    spec: &Specialization,
    rays: BufferHandle,
    count: u32,
) -> BufferHandle {
    let mut pass = g.compute_pass("ray_query", &RAY_QUERY);
    scene.read(&mut pass);
    pass.read("b_rays", rays);
    let hits = pass.create_buffer(
        "b_hits",
        "ray_query.hits",
        (count.max(1) as u64) * std::mem::size_of::<QueryHit>() as u64,
    );
    pass.specialization(spec).push(&count);
    pass.dispatch([count, 1, 1]);
    hits
}
