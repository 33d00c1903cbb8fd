//! The GPU BVH traversal returns the same hits as the CPU traversal, in both GPU layouts (binary and
//! compressed wide), on random rays through every built-in scene (reduced tessellation for the
//! large ones), axis-parallel rays and rays grazing triangles (aimed just inside an edge, or running
//! just above a surface, nearly parallel to it). The GPU traverses the renderer's packing (static
//! instances flattened into one BLAS, some kept as instances: walked directly, in turn when few,
//! or through the top level); hits must name the same original instance as the CPU's two-level
//! BVH over the original scene. Occlusion is checked both alone and as the pair walk BDPT's
//! camera pass uses answers it, each ray walked first and second beside another.

use ash::vk;
use glam::{Affine3A, Quat, Vec3};
use lucid_engine::bvh::{HitKind, Ray};
use lucid_engine::graph::{Executor, RenderGraph};
use lucid_engine::memory::Buffer;
use lucid_engine::scene::builtin::{self, BuildOptions};
use lucid_engine::scene::gpu::{pack_flat, BvhLayout, MAX_LOOSE_SPHERES};
use lucid_engine::scene::{Bvh, FlatScene, Material, Scene};
use lucid_engine::shader::{ShaderLibrary, SpecValue, Specialization};
use lucid_passes::debug::ray_query::{self, QueryHit, QueryRay, SPHERE_BIT};
use lucid_passes::plumbing::scene_buffers::{
    traversal_specialization, workgroup_scene_words, SceneBuffers,
};
use lucid_tests::{assert_no_validation_messages, context, run};
use std::sync::Arc;

/// A small deterministic generator (xorshift), so every run checks the same rays.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn direction(&mut self) -> Vec3 {
        let z = 2.0 * self.next() - 1.0;
        let phi = std::f32::consts::TAU * self.next();
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// Checks built-in scene `name` (reduced tessellation) with the renderer's packing in `layout`:
/// static instances flattened, those flagged in `dynamic` kept separate.
fn check_builtin(
    name: &str,
    dynamic: impl Fn(usize) -> bool,
    rays_per_scene: usize,
    layout: BvhLayout,
) -> Walk {
    let options = BuildOptions { detail: 0.02 };
    let mut scene = builtin::build_with(name, &options).unwrap();
    scene.validate().unwrap();
    let dynamic: Vec<bool> = (0..scene.instances.len()).map(dynamic).collect();
    check_scene(&scene, &dynamic, rays_per_scene, layout)
}

/// A ray grazing a random triangle of `scene`: aimed from `from` at a point just inside one of its
/// edges, or (every other one) running parallel to it just above its surface (through the flat
/// boxes of axis-aligned surfaces). Not closer to the triangle than a thousandth of its size:
/// nearer, the CPU's object-space and the GPU's world-space arithmetic round hits apart.
fn grazing_ray(
    scene: &Scene,
    rng: &mut Rng,
    from: Vec3,
    along_surface: bool,
) -> Option<(Vec3, Vec3)> {
    if scene.instances.is_empty() {
        return None;
    }
    let instance = &scene.instances[(rng.next() * scene.instances.len() as f32) as usize];
    let mesh = &scene.meshes[instance.mesh as usize];
    if mesh.indices.is_empty() {
        return None;
    }
    let t = ((rng.next() * mesh.indices.len() as f32) as usize).min(mesh.indices.len() - 1);
    let [a, b, c] = mesh
        .triangle(t)
        .map(|p| instance.transform.transform_point3(p));
    let normal = (b - a).cross(c - a).normalize_or_zero();
    if normal == Vec3::ZERO {
        return None;
    }
    // A point a thousandth of the way in from edge ab.
    let along = rng.next();
    let target = a + (b - a) * along * 0.999 + (c - a) * 1e-3;
    if !along_surface {
        return Some((from, (target - from).normalize()));
    }
    let size = (b - a).length().max((c - a).length());
    let dir = (b - a).normalize();
    Some((target + normal * 1e-3 * size - dir * size, dir))
}

/// How rays walked a packed scene: how they reached its instances, and whether they read its BLAS
/// and triangles from workgroup memory (`shaders/common/workgroup_scene.glsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Walk {
    top: TopLevel,
    in_workgroup: bool,
}

/// How rays reached the instances of a packed scene (`shaders/common/traverse.glsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TopLevel {
    /// One triangle instance, walked directly (`SINGLE_INSTANCE`).
    Single,
    /// A few instances, each walked in turn (`FEW_INSTANCES`).
    Few,
    /// The top-level BVH.
    Walked,
}

impl TopLevel {
    /// The walk the traversal's specialization constants select.
    fn of(spec: &Specialization) -> Self {
        let on = |name: &str| spec.get(name) == Some(SpecValue::Bool(true));
        if on("SINGLE_INSTANCE") {
            TopLevel::Single
        } else if on("FEW_INSTANCES") {
            TopLevel::Few
        } else {
            TopLevel::Walked
        }
    }
}

/// Traces random, axis-parallel and grazing rays through the validated `scene` packed as the
/// renderer packs it in `layout`, with the scene's specialization (the single-instance and
/// few-instance walks and the scene in workgroup memory included); returns the walk that
/// specialization selected.
fn check_scene(scene: &Scene, dynamic: &[bool], rays_per_scene: usize, layout: BvhLayout) -> Walk {
    let name = format!("{} ({layout})", scene.name);
    let name = name.as_str();
    let bvh = Bvh::build(scene);
    let flat = FlatScene::new(scene, dynamic);
    let flat_bvh = Bvh::build(&flat.scene);
    let (gpu, triangle_ids) = pack_flat(&flat, scene, &flat_bvh, layout);
    assert_eq!(gpu.layout(), layout);
    assert_eq!(
        gpu.features,
        scene.features(),
        "{name}: flattening must not hide features"
    );
    let spec = traversal_specialization(&gpu);
    let ctx = context(false);
    let buffers = SceneBuffers::upload(&ctx, &gpu, &triangle_ids).unwrap();
    let mut executor = Executor::new(&ctx, ShaderLibrary::new(&ctx, None).unwrap()).unwrap();

    let bounds = scene.bounds();
    let extent = bounds.max - bounds.min;
    let mut rng = Rng(0x9e3779b97f4a7c15 ^ name.len() as u64);
    let mut rays = Vec::with_capacity(rays_per_scene);
    for i in 0..rays_per_scene {
        // Half the rays start inside the bounds, half at the camera (the rays that matter most).
        let origin = if i % 2 == 0 {
            bounds.min + extent * Vec3::new(rng.next(), rng.next(), rng.next())
        } else {
            scene.camera.position
        };
        let t_max = if i % 3 == 0 {
            extent.length() * rng.next()
        } else {
            1e30
        };
        // Every eighth ray runs along an axis (infinite reciprocal components in the slab test),
        // every eighth other one grazes a triangle.
        let grazing = if i % 8 == 3 {
            grazing_ray(scene, &mut rng, origin, i % 16 == 3)
        } else {
            None
        };
        let (origin, dir) = if let Some(ray) = grazing {
            ray
        } else if i % 8 == 7 {
            let axis = [Vec3::X, Vec3::Y, Vec3::Z][(i / 8) % 3];
            (origin, if (i / 24) % 2 == 0 { axis } else { -axis })
        } else {
            (origin, rng.direction())
        };
        rays.push(Ray {
            origin,
            dir,
            t_min: 0.0,
            t_max,
        });
    }
    let query: Vec<QueryRay> = rays
        .iter()
        .map(|r| QueryRay {
            origin_tmax: r.origin.extend(r.t_max).to_array(),
            dir: r.dir.extend(0.0).to_array(),
        })
        .collect();
    let ray_buffer = Arc::new(
        Buffer::with_data(
            &ctx,
            "rays",
            "test",
            vk::BufferUsageFlags::STORAGE_BUFFER,
            bytemuck::cast_slice(&query),
        )
        .unwrap(),
    );
    let mut g = RenderGraph::new();
    let scene_handles = buffers.import(&mut g);
    let rays_handle = g.import_buffer("rays", ray_buffer);
    let hits = ray_query::add_ray_query(
        &mut g,
        &scene_handles,
        &spec,
        rays_handle,
        rays.len() as u32,
    );
    let readback = g.readback(hits);
    let outputs = run(&mut executor, g);
    let gpu_hits: Vec<QueryHit> = bytemuck::pod_collect_to_vec(outputs.bytes(readback).unwrap());

    let mut mismatches = Vec::new();
    let mut hits_seen = 0;
    for (i, (ray, got)) in rays.iter().zip(&gpu_hits).enumerate() {
        let want = bvh.intersect(scene, ray);
        let occluded = bvh.occluded(scene, ray);
        if want.is_some() {
            hits_seen += 1;
        }
        let same = match (&want, got.t >= 0.0) {
            (None, false) => true,
            (Some(h), true) => {
                let object = match h.kind {
                    HitKind::Triangle { instance, .. } => instance,
                    HitKind::Sphere { sphere } => SPHERE_BIT | sphere,
                };
                let t_close = (h.t - got.t).abs() <= 1e-3 * h.t.max(1.0);
                t_close && (object == got.object_id || (h.t - got.t).abs() <= 1e-5 * h.t.max(1.0))
            }
            _ => false,
        };
        let paired = if occluded { 3 } else { 0 };
        if !same || occluded != (got.occluded == 1) || got.paired != paired {
            mismatches.push(format!(
                "ray {i}: cpu {want:?} occluded {occluded}, gpu {got:?}"
            ));
        }
    }
    // Rays grazing an edge or a silhouette may round differently: allow one in a thousand.
    assert!(
        mismatches.len() * 1000 <= rays.len(),
        "{name}: {} of {} rays differ:\n{}",
        mismatches.len(),
        rays.len(),
        mismatches
            .iter()
            .take(10)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
    assert!(
        hits_seen * 10 > rays.len(),
        "{name}: a tenth of the rays should hit something ({hits_seen})"
    );
    drop((executor, buffers));
    assert_no_validation_messages(&ctx);
    Walk {
        top: TopLevel::of(&spec),
        in_workgroup: workgroup_scene_words(&gpu) != (0, 0),
    }
}

#[test]
fn gpu_traversal_matches_cpu_on_every_builtin_scene() {
    // Every third instance kept dynamic, so most scenes keep more than one instance.
    for layout in BvhLayout::ALL {
        let walks: Vec<TopLevel> = builtin::names()
            .iter()
            .map(|name| check_builtin(name, |i| i % 3 == 1, 4000, layout).top)
            .collect();
        for walk in [TopLevel::Few, TopLevel::Walked] {
            assert!(walks.contains(&walk), "no scene was traced with {walk:?}");
        }
    }
}

#[test]
fn single_instance_fast_path_matches_cpu() {
    for layout in BvhLayout::ALL {
        check_single_instance(layout);
    }
}

/// The single-instance fast path in `layout`: a static Cornell box, a static scene with a sphere
/// beside its triangles (tested one by one), one dynamic instance, alone and beside a sphere; with
/// more spheres than [`MAX_LOOSE_SPHERES`], the spheres' BLAS beside the triangles'. The Cornell
/// box's instances are walked in workgroup memory.
fn check_single_instance(layout: BvhLayout) {
    let small = |top| Walk {
        top,
        in_workgroup: true,
    };
    let large = |top| Walk {
        top,
        in_workgroup: false,
    };
    assert_eq!(
        check_builtin("cornell-box", |_| false, 4000, layout),
        small(TopLevel::Single),
        "a static Cornell box is one flattened instance"
    );
    assert_eq!(
        check_builtin("covered-light", |_| false, 4000, layout),
        large(TopLevel::Single),
        "a static scene with one sphere is one flattened instance and a loose sphere"
    );
    let mut crowded = builtin::build("cornell-box").unwrap();
    crowded.name = "Cornell box with many spheres".into();
    let material = crowded.add_material(Material::diffuse("sphere", Vec3::splat(0.5)));
    for k in 0..=MAX_LOOSE_SPHERES {
        let x = -0.8 + 1.6 * k as f32 / MAX_LOOSE_SPHERES as f32;
        crowded.add_sphere(Vec3::new(x, -0.8, 0.2 * (k % 3) as f32), 0.12, material);
    }
    crowded.validate().unwrap();
    assert_eq!(
        check_scene(
            &crowded,
            &vec![false; crowded.instances.len()],
            4000,
            layout
        ),
        large(TopLevel::Few),
        "more spheres than are tested one by one keep their BLAS"
    );
    // One dynamic instance, mirrored and rotated: the fast path keeps its transform.
    let mut cornell = builtin::build("cornell-box").unwrap();
    cornell.validate().unwrap();
    let mut scene = FlatScene::new(&cornell, &[]).scene;
    scene.name = "moved single instance".into();
    scene.instances[0].transform = Affine3A::from_scale_rotation_translation(
        Vec3::new(-1.0, 1.0, 1.0),
        Quat::from_rotation_y(0.3),
        Vec3::new(0.2, -0.1, 0.05),
    );
    assert_eq!(
        check_scene(&scene, &[true], 4000, layout),
        small(TopLevel::Single),
        "a lone dynamic instance is a single instance"
    );
    let material = scene.add_material(Material::diffuse("sphere", Vec3::splat(0.5)));
    scene.add_sphere(Vec3::new(0.3, -0.5, 0.1), 0.3, material);
    scene.name = "moved single instance beside a sphere".into();
    scene.validate().unwrap();
    assert_eq!(
        check_scene(&scene, &[true], 4000, layout),
        small(TopLevel::Single),
        "a lone dynamic instance beside a sphere is a single instance"
    );
}
