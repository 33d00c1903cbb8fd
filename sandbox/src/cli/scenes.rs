//! `lucid scenes`: the built-in scenes, their sizes and the features they use; with `--memory`, the
//! GPU memory of each as the renderer packs it, in both BVH layouts.

use clap::Args;
use lucid_engine::scene::gpu::{pack_flat, BvhLayout};
use lucid_engine::scene::{builtin, Bvh, FlatScene, Scene};

/// Options of `lucid scenes`.
#[derive(Debug, Args)]
pub struct ScenesArgs {
    /// Print as JSON.
    #[arg(long)]
    json: bool,
    /// Also build each scene's BVH and pack it as the renderer does (static instances flattened)
    /// in each BVH layout: GPU bytes per triangle (geometry and BVH) and in all (textures, lights
    /// and materials too). Takes seconds for the large scenes.
    #[arg(long)]
    memory: bool,
}

/// The GPU memory of `scene` packed as the renderer packs it, per BVH layout.
fn memory(scene: &Scene) -> serde_json::Value {
    let flat = FlatScene::new(scene, &[]);
    let bvh = Bvh::build(&flat.scene);
    let per_layout: serde_json::Map<String, serde_json::Value> = BvhLayout::ALL
        .into_iter()
        .map(|layout| {
            let (gpu, ids) = pack_flat(&flat, scene, &bvh, layout);
            let triangles = gpu.triangles.len().max(1) as f64;
            let total = gpu.total_bytes() + ids.len() * 8;
            let depths = gpu.bvh_depths();
            (
                layout.name().to_string(),
                serde_json::json!({
                    "bytes_per_triangle": gpu.bytes_per_triangle(),
                    "bvh_bytes": gpu.bvh_bytes(),
                    "total_bytes": total,
                    "total_bytes_per_triangle": total as f64 / triangles,
                    "blas_depth": depths.blas,
                    "tlas_depth": depths.tlas,
                }),
            )
        })
        .collect();
    per_layout.into()
}

/// Builds every built-in scene and lists it.
pub fn run(args: &ScenesArgs) -> anyhow::Result<()> {
    let mut rows = Vec::new();
    for name in builtin::names() {
        let scene = builtin::build(name)?;
        let features = scene.features();
        let mut row = serde_json::json!({
            "name": name,
            "triangles": scene.triangle_count(),
            "unique_triangles": scene.unique_triangle_count(),
            "spheres": scene.spheres.len(),
            "instances": scene.instances.len(),
            "features": features.to_string(),
        });
        if args.memory {
            row["gpu_memory"] = memory(&scene);
        }
        if !args.json {
            println!(
                "{name:<16} {:>10} triangles ({:>9} unique) {:>3} spheres  {features}",
                scene.triangle_count(),
                scene.unique_triangle_count(),
                scene.spheres.len()
            );
            if let Some(layouts) = row["gpu_memory"].as_object() {
                for (layout, m) in layouts {
                    println!(
                        "{:<16} {layout:<6} BVH: {:>6.1} bytes/triangle geometry + BVH, {:>6.1} in all \
                         ({:.1} MiB), BVH depth {} (top {})",
                        "",
                        m["bytes_per_triangle"].as_f64().unwrap_or(0.0),
                        m["total_bytes_per_triangle"].as_f64().unwrap_or(0.0),
                        m["total_bytes"].as_f64().unwrap_or(0.0) / (1 << 20) as f64,
                        m["blas_depth"],
                        m["tlas_depth"],
                    );
                }
            }
        }
        rows.push(row);
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
    }
    Ok(())
}
