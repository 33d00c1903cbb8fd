//! The two-level scene BVH: one BLAS per mesh (plus one over all spheres)
//! and a TLAS over instances, with CPU closest-hit and occlusion queries.

use glam::{Affine3A, Vec2};
use rayon::prelude::*;

use super::{Scene, SceneError};
use crate::bvh::{
    ray_sphere, ray_triangle, walk, Aabb, Blas, BlasGeometry, Hit, HitKind, Ray, Tlas,
};

/// What a BVH instance places.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InstanceSource {
    /// `Scene::instances[index]`.
    Mesh(u32),
    /// The single identity instance of the sphere BLAS.
    Spheres,
}

/// One TLAS entry: a BLAS placed in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BvhInstance {
    /// Index into `Bvh::blases`.
    pub blas: u32,
    /// Object-to-world transform.
    pub object_to_world: Affine3A,
    /// World-to-object transform.
    pub world_to_object: Affine3A,
    /// The scene object it stands for.
    pub source: InstanceSource,
}

/// A two-level BVH over a scene. It references, but does not own, the
/// scene geometry: queries take the scene it was built from.
#[derive(Clone, Debug)]
pub struct Bvh {
    /// Bottom levels: `blases[m]` is mesh `m`; the sphere BLAS, if any, is last.
    pub blases: Vec<Blas>,
    /// Top-level entries: scene instances in order, then the sphere instance.
    pub instances: Vec<BvhInstance>,
    /// The top level.
    pub tlas: Tlas,
}

impl Bvh {
    /// Builds all bottom levels (in parallel) and the top level.
    pub fn build(scene: &Scene) -> Self {
        let mut blases: Vec<Blas> = scene
            .meshes
            .par_iter()
            .enumerate()
            .map(|(i, m)| Blas::triangles(i as u32, &m.positions, &m.indices))
            .collect();
        if !scene.spheres.is_empty() {
            blases.push(Blas::spheres(&scene.spheres));
        }
        let mut bvh = Self {
            blases,
            instances: Vec::new(),
            tlas: Tlas::build(&[]),
        };
        bvh.place_instances(scene);
        bvh
    }

    /// Rebuilds only the top level after instances moved (or were added or
    /// removed). The meshes and spheres must be those the BVH was built
    /// from.
    pub fn rebuild_top_level(&mut self, scene: &Scene) -> Result<(), SceneError> {
        let expected = scene.meshes.len() + usize::from(!scene.spheres.is_empty());
        if expected != self.blases.len() {
            return Err(SceneError::Invalid(format!(
                "top-level rebuild needs the same meshes: BVH has {} bottom levels, scene needs {expected}",
                self.blases.len()
            )));
        }
        if let Some(i) = scene
            .instances
            .iter()
            .find(|i| i.mesh as usize >= scene.meshes.len())
        {
            return Err(SceneError::Invalid(format!(
                "instance `{}` uses a missing mesh",
                i.name
            )));
        }
        self.place_instances(scene);
        Ok(())
    }

    fn place_instances(&mut self, scene: &Scene) {
        self.instances = scene
            .instances
            .iter()
            .enumerate()
            .map(|(k, i)| BvhInstance {
                blas: i.mesh,
                object_to_world: i.transform,
                world_to_object: i.transform.inverse(),
                source: InstanceSource::Mesh(k as u32),
            })
            .collect();
        if !scene.spheres.is_empty() {
            self.instances.push(BvhInstance {
                blas: (self.blases.len() - 1) as u32,
                object_to_world: Affine3A::IDENTITY,
                world_to_object: Affine3A::IDENTITY,
                source: InstanceSource::Spheres,
            });
        }
        let bounds: Vec<Aabb> = self
            .instances
            .iter()
            .map(|i| {
                self.blases[i.blas as usize]
                    .bounds()
                    .transformed(&i.object_to_world)
            })
            .collect();
        self.tlas = Tlas::build(&bounds);
    }

    /// Total SAH cost: the top level's cost where each instance leaf entry
    /// additionally pays its bottom level's own (root-normalised) SAH cost,
    /// weighted by the probability of reaching that instance.
    pub fn sah_cost(&self) -> f32 {
        let nodes = &self.tlas.nodes;
        let root_area = nodes[0].bounds().surface_area();
        let mut cost = self.tlas.sah_cost();
        if root_area <= 0.0 {
            return cost;
        }
        for n in nodes.iter().filter(|n| n.is_leaf()) {
            let first = n.left_or_first as usize;
            for &e in &self.tlas.order[first..first + n.count as usize] {
                let inst = &self.instances[e as usize];
                let blas = &self.blases[inst.blas as usize];
                let area = blas
                    .bounds()
                    .transformed(&inst.object_to_world)
                    .surface_area();
                cost += area / root_area * blas.sah_cost();
            }
        }
        cost
    }

    /// Total number of BVH nodes (all levels).
    pub fn node_count(&self) -> usize {
        self.tlas.nodes.len() + self.blases.iter().map(|b| b.nodes.len()).sum::<usize>()
    }

    /// The closest hit along `ray`, or `None`.
    pub fn intersect(&self, scene: &Scene, ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut t_max = ray.t_max;
        walk(
            &self.tlas.nodes,
            ray.origin,
            ray.dir,
            ray.t_min,
            &mut t_max,
            |first, count, t_max| {
                for &e in &self.tlas.order[first as usize..(first + count) as usize] {
                    if let Some(h) = self.intersect_instance(scene, e, ray, *t_max, false) {
                        *t_max = h.t;
                        best = Some(h);
                    }
                }
                false
            },
        );
        best
    }

    /// Whether anything blocks `ray` within `(t_min, t_max)` (any hit).
    pub fn occluded(&self, scene: &Scene, ray: &Ray) -> bool {
        let mut t_max = ray.t_max;
        walk(
            &self.tlas.nodes,
            ray.origin,
            ray.dir,
            ray.t_min,
            &mut t_max,
            |first, count, t_max| {
                self.tlas.order[first as usize..(first + count) as usize]
                    .iter()
                    .any(|&e| {
                        self.intersect_instance(scene, e, ray, *t_max, true)
                            .is_some()
                    })
            },
        )
    }

    /// Intersects one instance; `any` stops at the first hit found.
    fn intersect_instance(
        &self,
        scene: &Scene,
        entry: u32,
        ray: &Ray,
        t_max: f32,
        any: bool,
    ) -> Option<Hit> {
        let inst = &self.instances[entry as usize];
        let blas = &self.blases[inst.blas as usize];
        // Object-space ray with an untouched direction scale, so `t` is
        // the same in both spaces.
        let origin = inst.world_to_object.transform_point3(ray.origin);
        let dir = inst.world_to_object.transform_vector3(ray.dir);
        let mut best: Option<(f32, u32, Vec2)> = None;
        let mut limit = t_max;
        walk(
            &blas.nodes,
            origin,
            dir,
            ray.t_min,
            &mut limit,
            |first, count, limit| {
                for &p in &blas.order[first as usize..(first + count) as usize] {
                    let hit = match blas.geometry {
                        BlasGeometry::Mesh(m) => {
                            let [a, b, c] = scene.meshes[m as usize].triangle(p as usize);
                            ray_triangle(origin, dir, a, b, c, ray.t_min, *limit)
                                .map(|(t, u, v)| (t, Vec2::new(u, v)))
                        }
                        BlasGeometry::Spheres => {
                            let s = &scene.spheres[p as usize];
                            ray_sphere(origin, dir, s.center, s.radius, ray.t_min, *limit)
                                .map(|t| (t, Vec2::ZERO))
                        }
                    };
                    if let Some((t, bary)) = hit {
                        *limit = t;
                        best = Some((t, p, bary));
                        if any {
                            return true;
                        }
                    }
                }
                false
            },
        );
        let (t, prim, barycentrics) = best?;
        let (kind, normal) = match (blas.geometry, inst.source) {
            (BlasGeometry::Mesh(m), InstanceSource::Mesh(i)) => {
                let [a, b, c] = scene.meshes[m as usize].triangle(prim as usize);
                let n = (b - a).cross(c - a);
                (
                    HitKind::Triangle {
                        instance: i,
                        triangle: prim,
                    },
                    inst.world_to_object.matrix3.transpose() * n,
                )
            }
            _ => {
                let s = &scene.spheres[prim as usize];
                (HitKind::Sphere { sphere: prim }, ray.at(t) - s.center)
            }
        };
        Some(Hit {
            t,
            kind,
            barycentrics,
            normal: normal.normalize_or_zero(),
        })
    }
}
