//! BVH build benchmark (std::time, no harness): builds the `classroom` and
//! `covered-light` scenes, times the two-level BVH build and reports
//! triangle counts and GPU bytes per stored triangle (geometry + BVH).
//!
//! Run: `cargo bench -p lucid-engine --bench bvh_build`.

use std::time::Instant;

use lucid_engine::scene::builtin::{self, BuildOptions};
use lucid_engine::scene::gpu::GpuScene;
use lucid_engine::scene::Bvh;

fn run(label: &str, name: &str, detail: f32) {
    let t = Instant::now();
    let scene = builtin::build_with(name, &BuildOptions { detail }).expect("built-in scene");
    let scene_s = t.elapsed().as_secs_f64();
    // Best of three BVH builds.
    let mut best = f64::INFINITY;
    let mut bvh = None;
    for _ in 0..3 {
        let t = Instant::now();
        let b = Bvh::build(&scene);
        best = best.min(t.elapsed().as_secs_f64());
        bvh = Some(b);
    }
    let bvh = bvh.expect("three builds");
    let t = Instant::now();
    let gpu = GpuScene::new(&scene, &bvh);
    let pack_s = t.elapsed().as_secs_f64();
    println!(
        "{label:<22} triangles {:>9} (stored {:>9})  scene {:>6.3} s  bvh build {:>6.3} s  pack {:>6.3} s  \
         nodes {:>9}  SAH {:>7.2}  bytes/triangle {:>6.1} (geometry {:.1} MiB + bvh {:.1} MiB)",
        scene.triangle_count(),
        scene.unique_triangle_count(),
        scene_s,
        best,
        pack_s,
        bvh.node_count(),
        bvh.sah_cost(),
        gpu.bytes_per_triangle(),
        gpu.geometry_bytes() as f64 / (1 << 20) as f64,
        gpu.bvh_bytes() as f64 / (1 << 20) as f64,
    );
}

fn main() {
    println!("threads: {}", rayon::current_num_threads());
    run("classroom", "classroom", 1.0);
    run("covered-light (1M)", "covered-light", 0.2);
    run("covered-light", "covered-light", 1.0);
}
