//! CPU BVH traversal against brute force on every built-in scene
//! (reduced detail), top-level rebuilds and SAH sanity.

use glam::{Affine3A, Vec2, Vec3};
use lucid_engine::bvh::{ray_sphere, ray_triangle, HitKind, Ray};
use lucid_engine::scene::builtin::{self, BuildOptions};
use lucid_engine::scene::{Bvh, Scene};

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn dir(&mut self) -> Vec3 {
        let z = 2.0 * self.next() - 1.0;
        let a = std::f32::consts::TAU * self.next();
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * a.cos(), r * a.sin(), z)
    }
}

/// Closest hit by testing every primitive (object space, as the BVH does).
fn brute_force(scene: &Scene, ray: &Ray) -> Option<(f32, HitKind)> {
    let mut best: Option<(f32, HitKind)> = None;
    for (ii, inst) in scene.instances.iter().enumerate() {
        let inv = inst.transform.inverse();
        let (o, d) = (
            inv.transform_point3(ray.origin),
            inv.transform_vector3(ray.dir),
        );
        let mesh = &scene.meshes[inst.mesh as usize];
        for t in 0..mesh.triangle_count() {
            let [a, b, c] = mesh.triangle(t);
            let limit = best.map_or(ray.t_max, |h| h.0);
            if let Some((th, _, _)) = ray_triangle(o, d, a, b, c, ray.t_min, limit) {
                best = Some((
                    th,
                    HitKind::Triangle {
                        instance: ii as u32,
                        triangle: t as u32,
                    },
                ));
            }
        }
    }
    for (si, s) in scene.spheres.iter().enumerate() {
        let limit = best.map_or(ray.t_max, |h| h.0);
        if let Some(th) = ray_sphere(ray.origin, ray.dir, s.center, s.radius, ray.t_min, limit) {
            best = Some((th, HitKind::Sphere { sphere: si as u32 }));
        }
    }
    best
}

fn rays(scene: &Scene, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    let b = scene.bounds();
    let ext = b.extent();
    (0..n)
        .map(|i| {
            if i % 3 == 0 {
                let ndc = Vec2::new(rng.next() * 2.0 - 1.0, rng.next() * 2.0 - 1.0);
                scene.camera.generate_ray(ndc, 1.0, Vec2::splat(0.5))
            } else {
                let o =
                    b.min + ext * Vec3::new(rng.next(), rng.next(), rng.next()) * 0.98 + ext * 0.01;
                let mut r = Ray::new(o, rng.dir());
                if i % 5 == 0 {
                    r.t_max = ext.length() * 0.2;
                }
                r
            }
        })
        .collect()
}

fn check(scene: &Scene, bvh: &Bvh, n: usize, seed: u64) {
    let mut hits = 0;
    for ray in rays(scene, n, seed) {
        let expected = brute_force(scene, &ray);
        let got = bvh.intersect(scene, &ray);
        match (expected, got) {
            (None, None) => {}
            (Some((t, kind)), Some(h)) => {
                hits += 1;
                assert!(
                    (t - h.t).abs() <= 1e-4 * t.max(1.0),
                    "{}: t {t} vs {}",
                    scene.name,
                    h.t
                );
                if (t - h.t).abs() == 0.0 {
                    assert_eq!(kind, h.kind, "{}", scene.name);
                }
                assert!(h.normal.is_normalized());
            }
            (e, g) => panic!("{}: brute force {e:?} vs bvh {g:?} for {ray:?}", scene.name),
        }
        assert_eq!(
            bvh.occluded(scene, &ray),
            expected.is_some(),
            "{}",
            scene.name
        );
    }
    assert!(hits > n / 4, "{}: only {hits} hits", scene.name);
}

#[test]
fn traversal_matches_brute_force_on_builtins() {
    let options = BuildOptions { detail: 0.002 };
    for name in builtin::names() {
        let scene = builtin::build_with(name, &options).unwrap();
        let bvh = Bvh::build(&scene);
        assert!(bvh.sah_cost() > 0.0, "{name}");
        let rays = if scene.triangle_count() > 20_000 {
            60
        } else {
            300
        };
        check(
            &scene,
            &bvh,
            rays,
            0x9e37_79b9_7f4a_7c15 ^ name.len() as u64,
        );
    }
}

#[test]
fn moving_an_instance_rebuilds_only_the_top_level() {
    let mut scene = builtin::build_with("cornell-teapot", &BuildOptions { detail: 0.05 }).unwrap();
    let mut bvh = Bvh::build(&scene);
    let blas_before: Vec<usize> = bvh.blases.iter().map(|b| b.nodes.len()).collect();
    let last = scene.instances.len() - 1;
    scene.instances[last].transform =
        Affine3A::from_translation(Vec3::new(0.0, 0.3, 0.0)) * scene.instances[last].transform;
    bvh.rebuild_top_level(&scene).unwrap();
    assert_eq!(
        blas_before,
        bvh.blases.iter().map(|b| b.nodes.len()).collect::<Vec<_>>()
    );
    check(&scene, &bvh, 300, 7);
    // A ray straight down through the moved teapot now hits it higher up.
    let moved = scene.instances[last]
        .transform
        .transform_point3(Vec3::new(0.0, 1.0, 0.0));
    let hit = bvh
        .intersect(
            &scene,
            &Ray::new(Vec3::new(moved.x, 0.98, moved.z), Vec3::NEG_Y),
        )
        .unwrap();
    assert!(matches!(hit.kind, HitKind::Triangle { instance, .. } if instance as usize == last));

    scene.meshes.pop();
    assert!(bvh.rebuild_top_level(&scene).is_err());
}

#[test]
fn sah_cost_prefers_a_real_bvh_over_a_single_leaf() {
    let scene = builtin::build_with("covered-light", &BuildOptions { detail: 0.002 }).unwrap();
    let bvh = Bvh::build(&scene);
    let tris = scene.triangle_count() as f32;
    assert!(
        bvh.sah_cost() < tris / 10.0,
        "{} for {tris} triangles",
        bvh.sah_cost()
    );
    assert!(bvh.node_count() < scene.unique_triangle_count() * 2);
}

#[test]
fn empty_scene_traverses_to_nothing() {
    let scene = Scene::new("empty");
    let bvh = Bvh::build(&scene);
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    assert!(bvh.intersect(&scene, &ray).is_none());
    assert!(!bvh.occluded(&scene, &ray));
}
