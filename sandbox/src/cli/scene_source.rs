//! Resolving `--scene`: a built-in scene name, or a `.gltf` / `.glb` file.

use anyhow::{bail, Context as _};
use lucid_engine::scene::{builtin, load_gltf, Scene};
use std::path::Path;

/// Loads the scene `arg` names: a built-in scene, or a glTF file. Warnings and notes (what the
/// importer supplied, e.g. a camera) go to stderr.
pub fn load(arg: &str) -> anyhow::Result<Scene> {
    let lower = arg.to_lowercase();
    let scene = if lower.ends_with(".gltf") || lower.ends_with(".glb") {
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
    for warning in &scene.warnings {
        eprintln!("warning: {warning}");
    }
    for note in &scene.notes {
        eprintln!("note: {note}");
    }
    Ok(scene)
}
