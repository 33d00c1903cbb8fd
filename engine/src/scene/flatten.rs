//! Flattening for the GPU: static mesh instances, emitters included, are merged into one
//! world-space mesh, so rays walk one BLAS instead of the top level over many overlapping instance
//! boxes (the Cornell box's walls and light, a classroom's desks and ceiling panels). Only instances
//! that move stay instances of their own: moving one rebuilds only the top level.
//!
//! The NEE light list is not built from the flattened scene but from the original one, with its
//! indices remapped through [`FlatScene::placement`] (see `crate::scene::gpu::pack_flat`).

use super::{Instance, Mesh, Scene};
use glam::{Affine3A, Vec3, Vec4};

/// Where an instance of the original scene went in a [`FlatScene`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placement {
    /// Merged into mesh 0 of the flattened scene; its triangle `t` is merged triangle
    /// `first_triangle + t`.
    Merged {
        /// The merged-mesh triangle of the instance's first triangle.
        first_triangle: u32,
    },
    /// Kept as instance `instance` of the flattened scene.
    Separate {
        /// Index into the flattened scene's instances.
        instance: u32,
    },
}

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
    /// Per instance of the original scene: where it went.
    pub placement: Vec<Placement>,
}

impl FlatScene {
    /// Flattens `scene`, keeping only the instances flagged in `dynamic` separate. `dynamic` may be
    /// shorter than the instance list (missing entries are static).
    pub fn new(scene: &Scene, dynamic: &[bool]) -> Self {
        let is_dynamic = |i: usize| dynamic.get(i).copied().unwrap_or(false);
        let merge: Vec<usize> = (0..scene.instances.len())
            .filter(|&i| !is_dynamic(i))
            .collect();
        let mut flat = scene.clone();
        flat.instances.clear();
        flat.meshes.clear();
        let mut merged_ids = Vec::new();
        let mut instance_origin = Vec::new();
        let mut placement = vec![Placement::Separate { instance: u32::MAX }; scene.instances.len()];
        let merged = !merge.is_empty();
        if merged {
            let mut mesh = Mesh {
                name: "flattened static instances".into(),
                positions: Vec::new(),
                normals: Vec::new(),
                material: 0,
                ..Default::default()
            };
            let any = |has: fn(&Mesh) -> bool| {
                merge
                    .iter()
                    .any(|&i| has(&scene.meshes[scene.instances[i].mesh as usize]))
            };
            let carried = Carried {
                colors: any(|m| !m.colors.is_empty()),
                alphas: any(|m| !m.alphas.is_empty()),
                tangents: any(|m| !m.tangents.is_empty()),
            };
            for &i in &merge {
                placement[i] = Placement::Merged {
                    first_triangle: mesh.indices.len() as u32,
                };
                append_instance(&mut mesh, scene, i, carried);
                let triangles = scene.meshes[scene.instances[i].mesh as usize].indices.len();
                let material = scene.instance_material(i);
                merged_ids.extend(std::iter::repeat_n([material, i as u32], triangles));
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
            placement[i] = Placement::Separate {
                instance: flat.instances.len() as u32,
            };
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
            placement,
        }
    }

    /// The instance of the flattened scene that original instance `original` became, if it was not
    /// merged.
    pub fn instance_of(&self, original: usize) -> Option<usize> {
        match self.placement.get(original) {
            Some(&Placement::Separate { instance }) => Some(instance as usize),
            _ => None,
        }
    }
}

/// The optional vertex attributes the merged mesh carries (because some merged mesh has them).
#[derive(Clone, Copy)]
struct Carried {
    colors: bool,
    alphas: bool,
    tangents: bool,
}

/// Appends instance `i` of `scene` to `mesh` in world space (positions, normals and tangents
/// transformed, missing UVs zero; vertex colours and alphas as `carried` says, missing ones white
/// and opaque; missing tangents zero).
fn append_instance(mesh: &mut Mesh, scene: &Scene, i: usize, carried: Carried) {
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
    let n = source.positions.len();
    if carried.colors {
        extend_or(&mut mesh.colors, &source.colors, n, Vec3::ONE);
    }
    if carried.alphas {
        extend_or(&mut mesh.alphas, &source.alphas, n, 1.0);
    }
    if carried.tangents {
        // A mirroring transform flips the handedness of the tangent frame.
        let handedness = inst.transform.matrix3.determinant().signum();
        let world: Vec<Vec4> = source
            .tangents
            .iter()
            .map(|t| {
                let v = inst.transform.transform_vector3(t.truncate());
                v.normalize_or_zero().extend(t.w * handedness)
            })
            .collect();
        extend_or(&mut mesh.tangents, &world, n, Vec4::ZERO);
    }
    mesh.indices
        .extend(source.indices.iter().map(|&t| t + base));
}

/// Appends `source` to `out` when it has all `n` vertices, else `n` copies of `missing`.
fn extend_or<T: Copy>(out: &mut Vec<T>, source: &[T], n: usize, missing: T) {
    if source.len() == n {
        out.extend_from_slice(source);
    } else {
        out.extend(std::iter::repeat_n(missing, n));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin;

    #[test]
    fn merges_static_instances_and_emitters_and_keeps_dynamic_ones() {
        let scene = builtin::build("cornell-box").unwrap();
        let n = scene.instances.len();
        let emitter = (0..n)
            .find(|&i| scene.materials[scene.instance_material(i) as usize].is_emissive())
            .expect("the Cornell box has a light");
        let dynamic = (emitter + 1) % n;
        let mut flags = vec![false; n];
        flags[dynamic] = true;
        let flat = FlatScene::new(&scene, &flags);
        assert!(flat.merged);
        assert_eq!(
            flat.scene.triangle_count(),
            scene.triangle_count(),
            "no triangle lost"
        );
        assert_eq!(flat.merged_ids.len(), flat.scene.meshes[0].indices.len());
        assert_eq!(
            flat.scene.instances.len(),
            2,
            "the merged and the dynamic one"
        );
        assert_eq!(flat.instance_of(dynamic), Some(1));
        assert_eq!(flat.instance_origin, vec![u32::MAX, dynamic as u32]);
        let Placement::Merged { first_triangle } = flat.placement[emitter] else {
            panic!("the static light is merged");
        };
        let light_mesh = &scene.meshes[scene.instances[emitter].mesh as usize];
        let first = first_triangle as usize;
        for t in 0..light_mesh.triangle_count() {
            assert_eq!(
                flat.merged_ids[first + t],
                [scene.instance_material(emitter), emitter as u32]
            );
            let world = light_mesh
                .triangle(t)
                .map(|p| scene.instances[emitter].transform.transform_point3(p));
            assert_eq!(flat.scene.meshes[0].triangle(first + t), world);
        }
    }

    #[test]
    fn a_static_scene_becomes_one_instance() {
        let scene = builtin::build("cornell-box").unwrap();
        let flat = FlatScene::new(&scene, &[]);
        assert_eq!(flat.scene.instances.len(), 1);
        assert_eq!(flat.scene.meshes.len(), 1);
        assert!((0..scene.instances.len()).all(|i| flat.instance_of(i).is_none()));
    }
}
