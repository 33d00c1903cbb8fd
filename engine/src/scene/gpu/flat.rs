//! GPU packing of a [`FlatScene`]: the merged instance gets its own kind, separate instances keep
//! their original ids, and the merged mesh's triangles carry (material, original instance) in GPU
//! order.

use super::GpuScene;
use crate::bvh::Bvh;
use crate::scene::{FlatScene, Scene};

/// `GpuInstance::kind` of the merged static instance: material and object id come per triangle from
/// the triangle-ids buffer.
pub const INSTANCE_FLATTENED: u32 = 2;

/// Packs `flat` (made from `original`, with `bvh` built from `flat.scene`); returns the scene and
/// the per-triangle ids of the merged mesh (`[material, original instance]`, indexed by GPU
/// triangle; at least one entry).
pub fn pack_flat(flat: &FlatScene, original: &Scene, bvh: &Bvh) -> (GpuScene, Vec<[u32; 2]>) {
    let mut gpu = GpuScene::new(&flat.scene, bvh);
    fix_instances(&mut gpu, flat, original);
    let mut ids = match (flat.merged, bvh.blases.first()) {
        (true, Some(blas)) => blas
            .order
            .iter()
            .map(|&t| flat.merged_ids[t as usize])
            .collect(),
        _ => Vec::new(),
    };
    if ids.is_empty() {
        ids.push([0, u32::MAX]);
    }
    (gpu, ids)
}

/// Re-applies the fix-ups after [`GpuScene::update_top_level`]: instance kinds and ids, and the
/// features, which must be those of the original scene (the merged instance hides the materials
/// of its triangles from a per-instance census).
pub fn fix_instances(gpu: &mut GpuScene, flat: &FlatScene, original: &Scene) {
    gpu.features = original.features();
    for inst in &mut gpu.instances {
        if inst.kind != 0 {
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
