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

/// Loads `spec`: a `.gltf` / `.glb` file, or a built-in scene name; lit by the environment map
/// `env` (`.hdr` or `.exr`) when given.
pub fn load(spec: &str, env: Option<&Path>) -> anyhow::Result<SceneInfo> {
    let lower = spec.to_ascii_lowercase();
    let mut scene: Scene = if lower.ends_with(".gltf") || lower.ends_with(".glb") {
        load_gltf(Path::new(spec)).with_context(|| format!("loading {spec}"))?
    } else {
        builtin::build(spec)?
    };
    if let Some(path) = env {
        scene.light_with_environment_file(path)?;
    }
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
        let info = load(DEFAULT_SCENE, None).unwrap();
        assert!(info.triangles > 0);
        let framed = info.framing(45.0);
        assert_eq!(framed, Camera::framing(&info.scene.bounds(), 45.0));
        let unknown = load("no-such-scene", None).unwrap_err().to_string();
        assert!(unknown.contains("no-such-scene"), "{unknown}");
        let missing = load("/nonexistent/file.glb", None).unwrap_err();
        assert!(format!("{missing:#}").contains("file.glb"));
        let file = std::env::temp_dir().join(format!("lucid-bad-{}.gltf", std::process::id()));
        std::fs::write(&file, b"{ not json").unwrap();
        assert!(load(file.to_str().unwrap(), None).is_err());
        std::fs::remove_file(&file).unwrap();
    }

    #[test]
    fn an_environment_map_lights_every_scene_opened() {
        let hdr = std::env::temp_dir().join(format!("lucid-sky-{}.hdr", std::process::id()));
        let texels = vec![image::Rgb([0.5f32; 3]); 8];
        let file = std::io::BufWriter::new(std::fs::File::create(&hdr).unwrap());
        image::codecs::hdr::HdrEncoder::new(file)
            .encode(&texels, 4, 2)
            .unwrap();
        let lit = load(DEFAULT_SCENE, Some(&hdr)).unwrap();
        assert!(lit.features.environment_map);
        assert!(
            lit.notes.iter().any(|n| n.contains("lights the scene")),
            "{:?}",
            lit.notes
        );
        std::fs::remove_file(&hdr).unwrap();
        let missing = load(DEFAULT_SCENE, Some(Path::new("/nonexistent/sky.hdr"))).unwrap_err();
        assert!(format!("{missing:#}").contains("sky.hdr"), "{missing:#}");
    }
}
