//! Flattening for the GPU: static, non-emissive mesh instances are merged into one world-space mesh,
//! so rays walk one BLAS instead of the top level over many overlapping instance boxes (the
//! Cornell box's walls, a classroom's desks). Instances that move, and emitters, stay instances of
//! their own: moving one rebuilds only the top level.

use super::{Instance, Mesh, Scene};
use glam::{Affine3A, Vec3};

/// A scene packed for the GPU, and how it maps back to the original.
#[derive(Clone, Debug)]
pub struct FlatScene {
    /// The scene whose first mesh and instance (when `merged` is true) hold every static instance.
    pub scene: Scene,
    /// Whether instance 0 / mesh 0 of `scene` is the merged mesh.
    pub merged: bool,
    /// Per triangle of the merged mesh: its material and original scene instance.
    pub merged_ids: Vec<[u32; 2]>,
    /// Per instance of `scene`: the original scene instance (`u32::MAX` for the merged one).
    pub instance_origin: Vec<u32>,
}

impl FlatScene {
    /// Flattens `scene`, keeping the instances flagged in `dynamic` (and every emissive one)
    /// separate. `dynamic` may be shorter than the instance list (missing entries are static).
    pub fn new(scene: &Scene, dynamic: &[bool]) -> Self {
        let is_dynamic = |i: usize| dynamic.get(i).copied().unwrap_or(false);
        let emissive = |i: usize| {
            let m = scene.instance_material(i) as usize;
            scene.materials.get(m).is_some_and(|m| m.is_emissive())
        };
        let merge: Vec<usize> = (0..scene.instances.len())
            .filter(|&i| !is_dynamic(i) && !emissive(i))
            .collect();
        let mut flat = scene.clone();
        flat.instances.clear();
        flat.meshes.clear();
        let mut merged_ids = Vec::new();
        let mut instance_origin = Vec::new();
        let merged = !merge.is_empty();
        if merged {
            let mut mesh = Mesh {
                name: "flattened static instances".into(),
                positions: Vec::new(),
                normals: Vec::new(),
                uvs: Vec::new(),
                indices: Vec::new(),
                material: 0,
            };
            for &i in &merge {
                let inst = &scene.instances[i];
                let source = &scene.meshes[inst.mesh as usize];
                let base = mesh.positions.len() as u32;
                let normal_matrix = inst.transform.matrix3.inverse().transpose();
                mesh.positions.extend(
                    source
                        .positions
                        .iter()
                        .map(|&p| inst.transform.transform_point3(p)),
                );
                mesh.normals.extend(source.normals.iter().map(|&n| {
                    let n = Vec3::from(normal_matrix * glam::Vec3A::from(n));
                    n.normalize_or_zero()
                }));
                if source.uvs.len() == source.positions.len() {
                    mesh.uvs.extend_from_slice(&source.uvs);
                } else {
                    mesh.uvs.extend(std::iter::repeat_n(
                        glam::Vec2::ZERO,
                        source.positions.len(),
                    ));
                }
                mesh.indices
                    .extend(source.indices.iter().map(|&t| t + base));
                let material = scene.instance_material(i);
                merged_ids.extend(std::iter::repeat_n(
                    [material, i as u32],
                    source.indices.len(),
                ));
            }
            flat.meshes.push(mesh);
            flat.instances.push(Instance {
                name: "flattened static instances".into(),
                mesh: 0,
                transform: Affine3A::IDENTITY,
                material: Some(0),
            });
            instance_origin.push(u32::MAX);
        }
        // Meshes used by the instances that stay separate.
        let mut mesh_map = vec![u32::MAX; scene.meshes.len()];
        for (i, inst) in scene.instances.iter().enumerate() {
            if merge.binary_search(&i).is_ok() {
                continue;
            }
            let m = inst.mesh as usize;
            if mesh_map[m] == u32::MAX {
                mesh_map[m] = flat.meshes.len() as u32;
                flat.meshes.push(scene.meshes[m].clone());
            }
            flat.instances.push(Instance {
                name: inst.name.clone(),
                mesh: mesh_map[m],
                transform: inst.transform,
                material: Some(scene.instance_material(i)),
            });
            instance_origin.push(i as u32);
        }
        Self {
            scene: flat,
            merged,
            merged_ids,
            instance_origin,
        }
    }

    /// The instance of the flattened scene that original instance `original` became, if it was not
    /// merged.
    pub fn instance_of(&self, original: usize) -> Option<usize> {
        self.instance_origin
            .iter()
            .position(|&o| o as usize == original)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin;

    #[test]
    fn merges_static_instances_and_keeps_emitters_and_dynamic_ones() {
        let scene = builtin::build("cornell-box").unwrap();
        let n = scene.instances.len();
        let mut dynamic = vec![false; n];
        dynamic[n - 1] = true;
        let flat = FlatScene::new(&scene, &dynamic);
        assert!(flat.merged);
        assert_eq!(
            flat.scene.triangle_count(),
            scene.triangle_count(),
            "no triangle lost"
        );
        assert_eq!(flat.merged_ids.len(), flat.scene.meshes[0].indices.len());
        assert!(
            flat.instance_of(n - 1).is_some(),
            "the dynamic instance stays separate"
        );
        let separate = (0..n)
            .filter(|&i| {
                dynamic[i] || scene.materials[scene.instance_material(i) as usize].is_emissive()
            })
            .count();
        assert!(separate >= 2, "the light and the dynamic instance");
        assert_eq!(flat.scene.instances.len(), 1 + separate);
    }
}
