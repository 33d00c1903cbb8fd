//! The scene being viewed: a built-in scene by name or a glTF file, loaded on the CPU for its
//! camera, statistics and feature list. A bad name or file is an error the panels show.

use anyhow::Context as _;
use lucid_engine::scene::{builtin, load_gltf, Camera, Scene, SceneFeatures};
use std::path::Path;

/// The scene `lucid` opens without arguments.
///
/// ```
/// assert!(lucid_engine::scene::builtin::names().contains(&lucid_sandbox::DEFAULT_SCENE));
/// ```
pub const DEFAULT_SCENE: &str = "cornell-box";

/// What the app knows about the loaded scene.
#[derive(Clone, Debug)]
pub struct SceneInfo {
    /// The name or file it was loaded from.
    pub source: String,
    /// The scene's name.
    pub name: String,
    /// Triangles after instancing.
    pub triangles: usize,
    /// Materials.
    pub materials: usize,
    /// Shading features used.
    pub features: SceneFeatures,
    /// The scene's own camera.
    pub camera: Camera,
    /// Import warnings.
    pub warnings: Vec<String>,
    /// What the importer supplied (a default camera or sky).
    pub notes: Vec<String>,
    /// The validated scene itself, for the renderer.
    pub scene: std::sync::Arc<Scene>,
}

impl SceneInfo {
    /// The camera that frames the whole scene from a three-quarter view with a vertical field of
    /// view of `vfov_degrees` (what a glTF file without a camera starts with, and the F key).
    pub fn framing(&self, vfov_degrees: f32) -> Camera {
        Camera::framing(&self.scene.bounds(), vfov_degrees)
    }
}

/// Loads `spec`: a `.gltf` / `.glb` file, or a built-in scene name.
pub fn load(spec: &str) -> anyhow::Result<SceneInfo> {
    let lower = spec.to_ascii_lowercase();
    let mut scene: Scene = if lower.ends_with(".gltf") || lower.ends_with(".glb") {
        load_gltf(Path::new(spec)).with_context(|| format!("loading {spec}"))?
    } else {
        builtin::build(spec)?
    };
    scene
        .validate()
        .with_context(|| format!("scene {spec} is invalid"))?;
    Ok(SceneInfo {
        source: spec.to_string(),
        name: scene.name.clone(),
        triangles: scene.triangle_count(),
        materials: scene.materials.len(),
        features: SceneFeatures::from_scene(&scene),
        camera: scene.camera,
        warnings: scene.warnings.clone(),
        notes: scene.notes.clone(),
        scene: std::sync::Arc::new(scene),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loads_builtins_and_reports_bad_input() {
        let info = load(DEFAULT_SCENE).unwrap();
        assert!(info.triangles > 0);
        let framed = info.framing(45.0);
        assert_eq!(framed, Camera::framing(&info.scene.bounds(), 45.0));
        let unknown = load("no-such-scene").unwrap_err().to_string();
        assert!(unknown.contains("no-such-scene"), "{unknown}");
        let missing = load("/nonexistent/file.glb").unwrap_err();
        assert!(format!("{missing:#}").contains("file.glb"));
        let file = std::env::temp_dir().join(format!("lucid-bad-{}.gltf", std::process::id()));
        std::fs::write(&file, b"{ not json").unwrap();
        assert!(load(file.to_str().unwrap()).is_err());
        std::fs::remove_file(&file).unwrap();
    }
}
