//! Resolving `--scene`: a built-in scene name, or a `.gltf` / `.glb` file; and `--env`.

use anyhow::{bail, Context as _};
use lucid_engine::scene::{builtin, load_gltf, Scene};
use std::path::Path;

/// Loads the scene `arg` names: a built-in scene, or a glTF file, lit by the environment map
/// `env` (a `.hdr` or `.exr` file) in place of its own environment when given. Warnings and notes
/// (what the importer supplied, e.g. a camera) go to stderr.
pub fn load(arg: &str, env: Option<&Path>) -> anyhow::Result<Scene> {
    let lower = arg.to_lowercase();
    let mut scene = if lower.ends_with(".gltf") || lower.ends_with(".glb") {
        let path = Path::new(arg);
        if !path.exists() {
            bail!("scene file {} does not exist", path.display());
        }
        load_gltf(path).with_context(|| format!("loading {}", path.display()))?
    } else {
        builtin::build(arg).map_err(|e| {
            anyhow::anyhow!(
                "{e} (a scene is a built-in name — {} — or a .gltf/.glb file)",
                builtin::names().join(", ")
            )
        })?
    };
    if let Some(path) = env {
        scene.light_with_environment_file(path)?;
    }
    for warning in &scene.warnings {
        eprintln!("warning: {warning}");
    }
    for note in &scene.notes {
        eprintln!("note: {note}");
    }
    Ok(scene)
}
