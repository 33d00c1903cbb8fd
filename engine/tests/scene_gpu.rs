//! The packed GPU layout: tracing the raw buffers (as a shader would)
//! agrees with the CPU BVH, lights and their table, textures, params and
//! memory per triangle.

use glam::{Affine3A, Vec2, Vec3, Vec4};
use lucid_engine::bvh::{ray_sphere, ray_triangle, Aabb};
use lucid_engine::capture::srgb_decode;
use lucid_engine::scene::builtin::{self, BuildOptions};
use lucid_engine::scene::gpu::bvh_pack::{Child, EMPTY};
use lucid_engine::scene::gpu::{
    apply_flattening, decode_normal, light_kind, pack_flat, texture_format, wide, BvhLayout,
    GpuBvhNode, GpuLight, GpuNodes, GpuScene, INSTANCE_FLATTENED,
};
use lucid_engine::scene::{Bvh, FlatScene, Scene};

const REDUCED: BuildOptions = BuildOptions { detail: 0.01 };

/// Walks `nodes` from `root` in their layout, calling `leaf(first, count)` for every leaf whose box
/// the ray enters (the wide walk is `wide::walk`, the shader's; it names primitives one by one).
fn walk(nodes: &GpuNodes, root: u32, o: Vec3, d: Vec3, mut leaf: impl FnMut(u32, u32)) {
    match nodes {
        GpuNodes::Binary(nodes) => walk_binary(nodes, root, o, d, leaf),
        GpuNodes::Wide(nodes) => {
            let mut t_max = f32::INFINITY;
            wide::walk(nodes, root, o, d, &mut t_max, |k, _| {
                leaf(k, 1);
                false
            });
        }
    }
}

/// Stack walk over the binary GPU layout `nodes` from the child word `root`, calling
/// `leaf(first, count)` for every leaf whose box the ray enters (the root is entered without a box
/// test).
fn walk_binary(nodes: &[GpuBvhNode], root: u32, o: Vec3, d: Vec3, mut leaf: impl FnMut(u32, u32)) {
    if root == EMPTY {
        return;
    }
    let inv = d.recip();
    let entered = |lo: [f32; 3], hi: [f32; 3]| {
        Aabb::new(lo.into(), hi.into())
            .intersect_ray(o, inv, 0.0, f32::INFINITY)
            .is_some()
    };
    let mut stack = vec![root];
    while let Some(word) = stack.pop() {
        match Child::from_word(word) {
            Child::Leaf { first, count } => leaf(first, count),
            Child::Node(i) => {
                let n = nodes[i as usize];
                if entered(n.left_min, n.left_max) {
                    stack.push(n.left);
                }
                if entered(n.right_min, n.right_max) {
                    stack.push(n.right);
                }
            }
        }
    }
}

fn apply(rows: &[[f32; 4]; 3], p: Vec4) -> Vec3 {
    Vec3::new(
        Vec4::from(rows[0]).dot(p),
        Vec4::from(rows[1]).dot(p),
        Vec4::from(rows[2]).dot(p),
    )
}

/// Closest hit distance using only the GPU buffers.
fn gpu_trace(g: &GpuScene, o: Vec3, d: Vec3) -> Option<f32> {
    let mut best = f32::INFINITY;
    if g.instances.is_empty() {
        return None;
    }
    walk(&g.tlas_nodes, g.tlas_root, o, d, |first, count| {
        for inst in &g.instances[first as usize..(first + count) as usize] {
            let lo = apply(&inst.world_to_object, o.extend(1.0));
            let ld = apply(&inst.world_to_object, d.extend(0.0));
            walk(&g.blas_nodes, inst.blas_root, lo, ld, |f, c| {
                for k in f..f + c {
                    if inst.kind == 0 {
                        let v = |j: usize| {
                            Vec3::from(
                                g.vertices[g.triangles[k as usize].vertices[j] as usize].position,
                            )
                        };
                        if let Some((t, _, _)) = ray_triangle(lo, ld, v(0), v(1), v(2), 0.0, best) {
                            best = t;
                        }
                    } else {
                        let s = g.spheres[k as usize].center_radius;
                        if let Some(t) =
                            ray_sphere(lo, ld, Vec3::new(s[0], s[1], s[2]), s[3], 0.0, best)
                        {
                            best = t;
                        }
                    }
                }
            });
        }
    });
    best.is_finite().then_some(best)
}

fn compare(scene: &Scene, bvh: &Bvh, g: &GpuScene) {
    let mut hits = 0;
    for i in 0..400 {
        let u = Vec2::new(
            (i % 20) as f32 / 19.0 * 2.0 - 1.0,
            (i / 20) as f32 / 19.0 * 2.0 - 1.0,
        );
        // Off the symmetric grid, so that no ray grazes an edge exactly (the GPU walk enters a
        // root without testing its box, the CPU tests it: at an exact edge they may disagree).
        let u = u * 0.95 + Vec2::new(0.0123, 0.0071);
        let ray = scene.camera.generate_ray(u, 1.0, Vec2::splat(0.5));
        let cpu = bvh.intersect(scene, &ray).map(|h| h.t);
        let gpu = gpu_trace(g, ray.origin, ray.dir);
        match (cpu, gpu) {
            (Some(a), Some(b)) => {
                hits += 1;
                assert!(
                    (a - b).abs() <= 1e-4 * a.max(1.0),
                    "{}: {a} vs {b}",
                    scene.name
                );
            }
            (None, None) => {}
            other => panic!("{}: {other:?}", scene.name),
        }
    }
    assert!(hits > 100, "{}: {hits}", scene.name);
}

#[test]
fn gpu_buffers_trace_like_the_cpu_bvh() {
    for layout in BvhLayout::ALL {
        for name in [
            "cornell-box",
            "cornell-teapot",
            "caustics",
            "classroom",
            "furnace",
            "covered-light",
        ] {
            let scene = builtin::build_with(name, &REDUCED).unwrap();
            let bvh = Bvh::build(&scene);
            let g = GpuScene::with_layout(&scene, &bvh, layout);
            assert_eq!(g.layout(), layout);
            assert_eq!(g.tlas_nodes.layout(), layout);
            g.check_depths().unwrap();
            assert_eq!(g.triangles.len(), scene.unique_triangle_count());
            compare(&scene, &bvh, &g);
        }
    }
}

#[test]
fn moving_an_instance_updates_the_top_level_only() {
    for layout in BvhLayout::ALL {
        move_an_instance(layout);
    }
}

fn move_an_instance(layout: BvhLayout) {
    let mut scene = builtin::build_with("cornell-teapot", &REDUCED).unwrap();
    let mut bvh = Bvh::build(&scene);
    let mut g = GpuScene::with_layout(&scene, &bvh, layout);
    let (blas, vertices) = (g.blas_nodes.clone(), g.vertices.clone());
    let last = scene.instances.len() - 1;
    scene.instances[last].transform =
        Affine3A::from_translation(Vec3::new(0.1, 0.2, 0.0)) * scene.instances[last].transform;
    bvh.rebuild_top_level(&scene).unwrap();
    g.update_top_level(&scene, &bvh);
    assert_eq!(g.blas_nodes, blas);
    assert_eq!(g.vertices, vertices);
    compare(&scene, &bvh, &g);
}

#[test]
fn cornell_light_table_splits_between_the_two_equal_triangles() {
    let scene = builtin::build("cornell-box").unwrap();
    let g = GpuScene::new(&scene, &Bvh::build(&scene));
    assert_eq!(g.lights.len(), 2, "the light quad is two triangles");
    let area = 0.46 * 0.38;
    // Power on the strongest channel, red.
    let power = std::f32::consts::PI * area * 18.387;
    assert!((g.params.light[0] - power).abs() < 1e-3 * power);
    // Selection: half by power, half uniform over the two triangles.
    let (uniform, power_scale) = (g.params.light[1], g.params.light[2]);
    assert!((uniform - 0.25).abs() < 1e-6 && (power_scale - 0.5 / power).abs() < 1e-6 / power);
    for (l, e) in g.lights.iter().zip(&g.light_table) {
        assert_eq!(l.kind, light_kind::TRIANGLE);
        assert!((l.p0[3] - area / 2.0).abs() < 1e-5);
        assert!((e.pdf - 0.5).abs() < 1e-5);
        for p in [l.p0, l.p1, l.p2] {
            assert!((p[1] - 0.99).abs() < 1e-5);
        }
        // The light's triangle index addresses its vertices in the GPU buffers.
        let inst = &g.instances[l.instance as usize];
        let v0 =
            Vec3::from(g.vertices[g.triangles[l.index as usize].vertices[0] as usize].position);
        let w0 = apply(&inst.object_to_world, v0.extend(1.0));
        assert!([l.p0, l.p1, l.p2]
            .iter()
            .any(|p| (Vec3::new(p[0], p[1], p[2]) - w0).length() < 1e-5));
    }
    assert_eq!(g.light_table.last().unwrap().cdf, 1.0);
}

#[test]
fn spheres_and_punctual_lights_pack() {
    let mut scene = builtin::build("caustics").unwrap();
    let glow = scene.add_material(lucid_engine::scene::Material::emissive("glow", Vec3::ONE));
    scene.add_sphere(Vec3::new(1.0, 0.2, 1.0), 0.2, glow);
    scene
        .punctual_lights
        .push(lucid_engine::scene::PunctualLight::Point {
            position: Vec3::new(0.0, 3.0, 0.0),
            intensity: Vec3::splat(5.0),
        });
    scene.validate().unwrap();
    let g = GpuScene::new(&scene, &Bvh::build(&scene));
    let kinds: Vec<u32> = g.lights.iter().map(|l| l.kind).collect();
    assert!(kinds.contains(&light_kind::SPHERE) && kinds.contains(&light_kind::POINT));
    let sphere_light = g
        .lights
        .iter()
        .find(|l| l.kind == light_kind::SPHERE)
        .unwrap();
    assert_eq!(g.spheres[sphere_light.index as usize].scene_sphere, 1);
    let sum: f32 = g.light_table.iter().map(|e| e.pdf).sum();
    assert!((sum - 1.0).abs() < 1e-5);
    assert!(g.features.delta_lights && g.features.spheres);
}

#[test]
fn textures_and_params_pack() {
    let scene = builtin::build_with("classroom", &REDUCED).unwrap();
    let g = GpuScene::new(&scene, &Bvh::build(&scene));
    assert_eq!(g.textures.len(), 1);
    assert_eq!(g.textures[0].format, texture_format::RGBA8_SRGB);
    // The sRGB decoding table, then level 0 and its mip chain down to 1x1.
    assert_eq!(g.textures[0].offset, 256);
    assert_eq!(
        g.texels.len(),
        256 + 64 * 64 + 32 * 32 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1
    );
    for code in [0u8, 10, 11, 128, 255] {
        let linear = f32::from_bits(g.texels[usize::from(code)]);
        assert_eq!(linear, srgb_decode(f32::from(code) / 255.0), "code {code}");
    }
    assert_eq!(f32::from_bits(g.texels[255]), 1.0);
    assert_eq!(g.params.environment.kind, 1);
    assert_eq!(g.params.sun.radiance_enabled[3], 1.0);
    let cam = scene.camera;
    assert!((g.params.camera.up_tan_half_fov[3] - (cam.vfov * 0.5).tan()).abs() < 1e-6);
    assert_eq!(g.params.counts0[0] as usize, scene.unique_triangle_count());
    assert!(g.total_bytes() > g.geometry_bytes() + g.bvh_bytes());
}

#[test]
fn memory_per_triangle_is_under_100_bytes() {
    let scene = builtin::build_with("covered-light", &REDUCED).unwrap();
    let bvh = Bvh::build(&scene);
    let binary = GpuScene::with_layout(&scene, &bvh, BvhLayout::Binary);
    let wide = GpuScene::with_layout(&scene, &bvh, BvhLayout::Wide);
    for g in [&binary, &wide] {
        let bpt = g.bytes_per_triangle();
        assert!(bpt > 30.0 && bpt < 100.0, "{}: {bpt}", g.layout());
    }
    assert!(
        wide.bvh_bytes() * 3 < binary.bvh_bytes(),
        "compressed wide nodes take under a third of the binary ones: {} vs {}",
        wide.bvh_bytes(),
        binary.bvh_bytes()
    );
}

#[test]
fn furnace_packs_a_single_sphere_instance() {
    let scene = builtin::build("furnace").unwrap();
    let g = GpuScene::new(&scene, &Bvh::build(&scene));
    assert_eq!(g.instances.len(), 1);
    assert_eq!(g.instances[0].kind, 1);
    assert!(
        !g.single_instance(),
        "a sphere instance takes the top level"
    );
    assert!(g.lights.is_empty() && g.triangles.is_empty());
    assert_eq!(g.bytes_per_triangle(), 0.0);
    assert_eq!(
        gpu_trace(&g, Vec3::new(0.0, 0.0, 4.0), Vec3::NEG_Z),
        Some(3.0)
    );
}

/// A light as comparable bits: kind, world vertices with area and emitting side, emission with
/// power, and its selection pdf.
fn light_records(g: &GpuScene) -> Vec<Vec<u32>> {
    let mut records: Vec<Vec<u32>> = g
        .lights
        .iter()
        .zip(&g.light_table)
        .map(|(l, e)| {
            let floats = [l.p0, l.p1, l.p2, l.emission].concat();
            std::iter::once(l.kind)
                .chain(floats.iter().map(|f| f.to_bits()))
                .chain(std::iter::once(e.pdf.to_bits()))
                .collect()
        })
        .collect();
    records.sort();
    records
}

/// World-space vertices of GPU triangle `t` of instance `slot`.
fn gpu_triangle(g: &GpuScene, slot: u32, t: u32) -> [Vec3; 3] {
    let inst = &g.instances[slot as usize];
    std::array::from_fn(|k| {
        let v = g.vertices[g.triangles[t as usize].vertices[k] as usize].position;
        apply(&inst.object_to_world, Vec3::from(v).extend(1.0))
    })
}

/// Checks that a triangle light names the GPU triangle it stands for, and that its emitting side is
/// the side the packed shading normals point to.
fn check_light_triangle(g: &GpuScene, ids: &[[u32; 2]], scene: &Scene, l: &GpuLight) {
    let p = [l.p0, l.p1, l.p2].map(|p| Vec3::new(p[0], p[1], p[2]));
    let q = gpu_triangle(g, l.instance, l.index);
    for (a, b) in p.iter().zip(&q) {
        assert!(
            (*a - *b).length() <= 1e-4 * a.length().max(1.0),
            "{p:?} vs {q:?}"
        );
    }
    let inst = &g.instances[l.instance as usize];
    let original = if inst.kind == INSTANCE_FLATTENED {
        ids[l.index as usize][1]
    } else {
        inst.scene_instance
    };
    let material = &scene.materials[scene.instance_material(original as usize) as usize];
    assert_eq!(material.emission.to_array(), l.emission[..3]);
    let shading: Vec3 = (0..3)
        .map(|k| {
            decode_normal(g.vertices[g.triangles[l.index as usize].vertices[k] as usize].normal)
        })
        .sum();
    // Normals transform by the transposed world-to-object matrix.
    let world_shading: Vec3 = (0..3)
        .map(|k| Vec3::from_slice(&inst.world_to_object[k][..3]) * shading[k])
        .sum();
    let front = (p[1] - p[0]).cross(p[2] - p[0]) * l.p1[3];
    assert!(front.dot(world_shading) > 0.0, "emitting side of {p:?}");
}

/// The flattened packing (emitters merged, `dynamic` instances separate) has the same NEE lights as
/// the packing of the original scene, and each light addresses its packed triangle, in both
/// layouts (each orders the triangles its own way).
fn check_flat_lights(scene: &Scene, dynamic: &[bool]) {
    for layout in BvhLayout::ALL {
        check_flat_lights_in(scene, dynamic, layout);
    }
}

fn check_flat_lights_in(scene: &Scene, dynamic: &[bool], layout: BvhLayout) {
    let reference = GpuScene::with_layout(scene, &Bvh::build(scene), BvhLayout::Binary);
    let flat = FlatScene::new(scene, dynamic);
    let (g, ids) = pack_flat(&flat, scene, &Bvh::build(&flat.scene), layout);
    assert!(!g.lights.is_empty(), "{}: has lights", scene.name);
    assert_eq!(
        light_records(&g),
        light_records(&reference),
        "{}",
        scene.name
    );
    assert_eq!(g.params.light, reference.params.light);
    assert_eq!(g.params.counts0[3], reference.params.counts0[3]);
    for l in g.lights.iter().filter(|l| l.kind == light_kind::TRIANGLE) {
        check_light_triangle(&g, &ids, scene, l);
    }
}

#[test]
fn flattening_keeps_the_light_list() {
    let cornell = builtin::build("cornell-box").unwrap();
    check_flat_lights(&cornell, &[]);
    let classroom = builtin::build_with("classroom", &REDUCED).unwrap();
    check_flat_lights(&classroom, &[]);
    let dynamic: Vec<bool> = (0..classroom.instances.len()).map(|i| i % 3 == 1).collect();
    check_flat_lights(&classroom, &dynamic);
}

#[test]
fn flattening_keeps_the_emitting_side_of_mirrored_lights() {
    let mut scene = builtin::build("cornell-box").unwrap();
    let mirror = Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0));
    for inst in &mut scene.instances {
        inst.transform = mirror * inst.transform;
    }
    check_flat_lights(&scene, &[]);
    let light = (0..scene.instances.len())
        .find(|&i| scene.materials[scene.instance_material(i) as usize].is_emissive())
        .unwrap();
    let mut dynamic = vec![false; scene.instances.len()];
    dynamic[light] = true;
    check_flat_lights(&scene, &dynamic);
}

#[test]
fn a_flattened_static_scene_is_a_single_instance() {
    let scene = builtin::build("cornell-box").unwrap();
    let flat = FlatScene::new(&scene, &[]);
    let (g, _) = pack_flat(
        &flat,
        &scene,
        &Bvh::build(&flat.scene),
        BvhLayout::default(),
    );
    assert!(g.single_instance());
    assert!(!GpuScene::new(&scene, &Bvh::build(&scene)).single_instance());
}

#[test]
fn moving_a_dynamic_light_moves_its_light_entries() {
    let mut scene = builtin::build("cornell-box").unwrap();
    let light = (0..scene.instances.len())
        .find(|&i| scene.materials[scene.instance_material(i) as usize].is_emissive())
        .unwrap();
    let mut dynamic = vec![false; scene.instances.len()];
    dynamic[light] = true;
    let mut flat = FlatScene::new(&scene, &dynamic);
    let mut bvh = Bvh::build(&flat.scene);
    let (mut g, ids) = pack_flat(&flat, &scene, &bvh, BvhLayout::default());
    let before = light_records(&g);
    let moved =
        Affine3A::from_translation(Vec3::new(0.1, -0.2, 0.05)) * scene.instances[light].transform;
    scene.instances[light].transform = moved;
    let separate = flat.instance_of(light).unwrap();
    flat.scene.instances[separate].transform = moved;
    bvh.rebuild_top_level(&flat.scene).unwrap();
    apply_flattening(&mut g, &flat, &scene, &bvh);
    let reference = GpuScene::new(&scene, &Bvh::build(&scene));
    assert_ne!(light_records(&g), before);
    assert_eq!(light_records(&g), light_records(&reference));
    for l in &g.lights {
        check_light_triangle(&g, &ids, &scene, l);
    }
}
