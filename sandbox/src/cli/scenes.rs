//! `lucid scenes`: the built-in scenes, their sizes and the features they use.

use clap::Args;
use lucid_engine::scene::builtin;

/// Options of `lucid scenes`.
#[derive(Debug, Args)]
pub struct ScenesArgs {
    /// Print as JSON.
    #[arg(long)]
    json: bool,
}

/// Builds every built-in scene and lists it.
pub fn run(args: &ScenesArgs) -> anyhow::Result<()> {
    let mut rows = Vec::new();
    for name in builtin::names() {
        let scene = builtin::build(name)?;
        let features = scene.features();
        rows.push(serde_json::json!({
            "name": name,
            "triangles": scene.triangle_count(),
            "unique_triangles": scene.unique_triangle_count(),
            "spheres": scene.spheres.len(),
            "instances": scene.instances.len(),
            "features": features.to_string(),
        }));
        if !args.json {
            println!(
                "{name:<16} {:>10} triangles ({:>9} unique) {:>3} spheres  {features}",
                scene.triangle_count(),
                scene.unique_triangle_count(),
                scene.spheres.len()
            );
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
    }
    Ok(())
}
