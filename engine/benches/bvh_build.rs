//! BVH build benchmark (std::time, no harness): builds the `classroom` and `covered-light` scenes
//! (1 M and 5 M triangles) as the renderer does (static instances flattened into one mesh), times
//! the binary SAH build, the packing for the GPU in each layout (binary; wide: collapse,
//! quantization and reordering) and the bare collapse of the bottom levels, and reports triangle
//! counts, tree depths and GPU bytes per triangle (geometry + BVH) per layout.
//!
//! Run: `cargo bench -p lucid-engine --bench bvh_build`.

use std::time::Instant;

use lucid_engine::scene::builtin::{self, BuildOptions};
use lucid_engine::scene::gpu::{pack_flat, wide, BvhLayout};
use lucid_engine::scene::{Bvh, FlatScene};

/// The best of three timings of `f` in seconds, with its last result.
fn best_of_three<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..3 {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("three runs"))
}

fn run(label: &str, name: &str, detail: f32) {
    let t = Instant::now();
    let scene = builtin::build_with(name, &BuildOptions { detail }).expect("built-in scene");
    let flat = FlatScene::new(&scene, &[]);
    let scene_s = t.elapsed().as_secs_f64();
    let (build_s, bvh) = best_of_three(|| Bvh::build(&flat.scene));
    println!(
        "{label:<22} triangles {:>9} (stored {:>9})  scene {scene_s:>6.3} s  bvh build {build_s:>6.3} s  \
         binary nodes {:>9}  SAH {:>7.2}",
        scene.triangle_count(),
        scene.unique_triangle_count(),
        bvh.node_count(),
        bvh.sah_cost(),
    );
    let (collapse_s, wide_nodes) = best_of_three(|| {
        let mut nodes = Vec::new();
        for blas in &bvh.blases {
            wide::pack_tree(&blas.nodes, 0, &mut nodes);
        }
        nodes.len()
    });
    println!(
        "{:<22} collapse of the bottom levels alone {collapse_s:>6.3} s ({wide_nodes} wide nodes)",
        ""
    );
    for layout in BvhLayout::ALL {
        let (pack_s, (gpu, _)) = best_of_three(|| pack_flat(&flat, &scene, &bvh, layout));
        let depths = gpu.bvh_depths();
        println!(
            "{:<22} {layout:<6} pack {pack_s:>6.3} s  build + pack {:>6.3} s  nodes {:>9}  depth {:>3} (top {:>2})  \
             bytes/triangle {:>6.1} (geometry {:.1} MiB + bvh {:.1} MiB)",
            "",
            build_s + pack_s,
            gpu.blas_nodes.len() + gpu.tlas_nodes.len(),
            depths.blas,
            depths.tlas,
            gpu.bytes_per_triangle(),
            gpu.geometry_bytes() as f64 / (1 << 20) as f64,
            gpu.bvh_bytes() as f64 / (1 << 20) as f64,
        );
    }
}

fn main() {
    println!("threads: {}", rayon::current_num_threads());
    run("classroom", "classroom", 1.0);
    run("covered-light (1M)", "covered-light", 0.2);
    run("covered-light", "covered-light", 1.0);
}
