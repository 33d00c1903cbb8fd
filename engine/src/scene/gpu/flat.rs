//! GPU packing of a [`FlatScene`]: the merged instance gets its own kind, separate instances keep
//! their original ids, the merged mesh's triangles carry (material, original instance) in GPU
//! order, and the NEE lights are those of the original scene, remapped to the packed one.

use super::{emitter_inverse_orders, BvhLayout, GpuScene, INSTANCE_TRIANGLES};
use crate::scene::{Bvh, FlatScene, Placement, Scene};

/// `GpuInstance::kind` of the merged static instance: material and object id come per triangle from
/// the triangle-ids buffer.
pub const INSTANCE_FLATTENED: u32 = 2;

/// Packs `flat` (made from `original`, with `bvh` built from `flat.scene`) with its BVH in
/// `layout`; returns the scene and the per-triangle ids of the merged mesh (`[material, original
/// instance]`, indexed by GPU triangle; at least one entry).
pub fn pack_flat(
    flat: &FlatScene,
    original: &Scene,
    bvh: &Bvh,
    layout: BvhLayout,
) -> (GpuScene, Vec<[u32; 2]>) {
    let mut gpu = GpuScene::without_top_level(&flat.scene, bvh, layout);
    apply_flattening(&mut gpu, flat, original, bvh);
    let mut ids = match (flat.merged, gpu.blas_orders.first()) {
        (true, Some(order)) => order.iter().map(|&t| flat.merged_ids[t as usize]).collect(),
        _ => Vec::new(),
    };
    if ids.is_empty() {
        ids.push([0, u32::MAX]);
    }
    (gpu, ids)
}

/// The flattened counterpart of [`GpuScene::update_top_level`] (call it after
/// [`Bvh::rebuild_top_level`] of `flat.scene`): packs the TLAS and the instances of `flat.scene`
/// with their kinds and original ids, the NEE lights of `original` (its transforms and materials,
/// remapped to the packed instances and triangles), the params, and the features of `original`
/// (the merged instance hides the materials of its triangles from a per-instance census).
pub fn apply_flattening(gpu: &mut GpuScene, flat: &FlatScene, original: &Scene, bvh: &Bvh) {
    gpu.features = original.features();
    let slots = gpu.place_instances(&flat.scene, bvh);
    mark_instances(gpu, flat);
    let flat_mesh = |i: usize| match flat.placement[i] {
        Placement::Merged { .. } => 0,
        Placement::Separate { instance } => flat.scene.instances[instance as usize].mesh as usize,
    };
    let inverse_orders = emitter_inverse_orders(original, &gpu.blas_orders, flat_mesh);
    let instance_slots: Vec<u32> = flat
        .placement
        .iter()
        .map(|p| match *p {
            Placement::Merged { .. } => slots[0],
            Placement::Separate { instance } => slots[instance as usize],
        })
        .collect();
    let triangle = |i: u32, t: u32| {
        let (mesh, t) = match flat.placement[i as usize] {
            Placement::Merged { first_triangle } => (0, first_triangle + t),
            Placement::Separate { .. } => (flat_mesh(i as usize), t),
        };
        gpu.triangle_base[mesh] + inverse_orders[mesh][t as usize]
    };
    let (lights, table, light) = gpu.pack_lights(original, &instance_slots, &triangle);
    gpu.set_lights(original, lights, table, light);
}

/// Gives the merged instance its kind and the separate ones their original scene instance.
fn mark_instances(gpu: &mut GpuScene, flat: &FlatScene) {
    for inst in &mut gpu.instances {
        if inst.kind != INSTANCE_TRIANGLES {
            continue;
        }
        match flat.instance_origin.get(inst.scene_instance as usize) {
            Some(&u32::MAX) => {
                inst.kind = INSTANCE_FLATTENED;
                inst.scene_instance = u32::MAX;
            }
            Some(&original) => inst.scene_instance = original,
            None => {}
        }
    }
}
