//! glTF 2.0 import (`.gltf` with external or embedded base64 buffers and
//! images, and `.glb`).
//!
//! The importer never panics on bad input: the GLB container, accessors,
//! buffer views, indices, URIs and transforms are all checked here rather
//! than trusting the `gltf` crate's loaders, and each failure becomes a
//! [`SceneError::Gltf`] naming the file and the problem. Required
//! extensions other than [`SUPPORTED_EXTENSIONS`] are rejected by name. A
//! scene without any light (no emissive surface, punctual light or sun) gets
//! [`Environment::NEUTRAL_SKY`], and a note in `Scene::notes` says so.
//!
//! What is imported: triangle, strip and fan primitives (positions, normals, `TEXCOORD_0`,
//! indices) as meshes, the default scene's node hierarchy as instances
//! with world transforms, the first perspective camera (without one, [`Camera::framing`] frames
//! the scene's bounds and a note in `Scene::notes` says so), materials (see
//! [`materials`]) with base-colour textures, and `KHR_lights_punctual`
//! point and spot lights (the first directional light becomes the sun).
//! Light intensities are photometric, as the extension specifies: candela for
//! point and spot lights, lux for directional ones; they become radiometric
//! values through [`crate::scene::LUMENS_PER_WATT`] (see [`crate::scene::PunctualLight`]).

mod accessor;
mod container;
pub mod materials;
mod meshes;
mod nodes;
mod texture_slot;
mod unsupported;
mod uri;

use std::collections::HashMap;
use std::path::Path;

use gltf::buffer::Source;
use gltf::json::mesh::Semantic;
use gltf::json::validation::Checked;

use super::{Camera, Environment, Scene, SceneError};
use materials::MaterialImporter;
use nodes::NodeImporter;
use unsupported::{Feature, Unsupported};

/// Vertical field of view of the camera that frames a file without one.
pub const DEFAULT_VFOV_DEGREES: f32 = 45.0;

/// Extensions the importer understands (and so accepts as required).
pub const SUPPORTED_EXTENSIONS: [&str; 6] = [
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_texture_transform",
];

/// Imports a `.gltf` or `.glb` file; external files resolve relative to it.
pub fn load_gltf(path: &Path) -> Result<Scene, SceneError> {
    let label = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| SceneError::Gltf {
        file: label.clone(),
        message: format!("cannot read file: {e}"),
    })?;
    let glb = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    if glb && !bytes.starts_with(&container::GLB_MAGIC) {
        return Err(SceneError::Gltf {
            file: label,
            message: format!(
                "not a binary glTF: bad magic {:?} (a .glb file starts with \"glTF\")",
                String::from_utf8_lossy(&bytes[..bytes.len().min(4)])
            ),
        });
    }
    load_gltf_slice(&bytes, path.parent(), &label)
}

/// Imports glTF or GLB bytes. `base` resolves relative URIs (without it
/// only embedded data is allowed); `label` names the input in messages and
/// becomes the scene name.
pub fn load_gltf_slice(
    bytes: &[u8],
    base: Option<&Path>,
    label: &str,
) -> Result<Scene, SceneError> {
    import(bytes, base, label).map_err(|message| SceneError::Gltf {
        file: label.to_owned(),
        message,
    })
}

fn import(bytes: &[u8], base: Option<&Path>, label: &str) -> Result<Scene, String> {
    let c = container::split(bytes)?;
    let root =
        gltf::json::Root::from_slice(c.json).map_err(|e| format!("invalid glTF JSON: {e}"))?;
    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| !SUPPORTED_EXTENSIONS.contains(&e.as_str()))
    {
        return Err(format!(
            "required extension `{ext}` is not supported (supported: {})",
            SUPPORTED_EXTENSIONS.join(", ")
        ));
    }
    let mut scene = Scene::new(label);
    for ext in root
        .extensions_used
        .iter()
        .filter(|e| !SUPPORTED_EXTENSIONS.contains(&e.as_str()))
    {
        scene.warnings.push(format!(
            "{label}: extension `{ext}` is not supported; ignored"
        ));
    }
    // gltf-json's own validation indexes `accessors` with the POSITION
    // accessor unchecked; catch that case first.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let pos = prim.attributes.get(&Checked::Valid(Semantic::Positions));
            if let Some(a) = pos.filter(|a| a.value() >= root.accessors.len()) {
                return Err(format!(
                    "mesh {m} primitive {p}: POSITION accessor {} does not exist",
                    a.value()
                ));
            }
        }
    }
    let doc = gltf::Document::from_json(root).map_err(|e| e.to_string())?;
    let buffers = doc
        .buffers()
        .map(|b| {
            let data = match b.source() {
                Source::Bin => c.bin.map(<[u8]>::to_vec).ok_or_else(|| {
                    format!(
                        "buffer {} refers to a GLB binary chunk, but there is none",
                        b.index()
                    )
                })?,
                Source::Uri(u) => {
                    uri::read(u, base).map_err(|e| format!("buffer {}: {e}", b.index()))?
                }
            };
            if data.len() < b.length() {
                return Err(format!(
                    "buffer {}: holds {} bytes but byteLength is {}",
                    b.index(),
                    data.len(),
                    b.length()
                ));
            }
            Ok(data)
        })
        .collect::<Result<Vec<_>, String>>()?;
    let gscene = doc
        .default_scene()
        .or_else(|| doc.scenes().next())
        .ok_or("the file has no scene")?;
    let mut importer = NodeImporter {
        doc: &doc,
        buffers: &buffers,
        materials: MaterialImporter::new(&doc, &buffers, base),
        mesh_cache: HashMap::new(),
        material_cache: HashMap::new(),
        camera_found: false,
        unsupported: Unsupported::default(),
    };
    importer.walk(&mut scene, gscene.nodes().collect())?;
    if doc.animations().next().is_some() {
        importer
            .unsupported
            .note(Feature::Animations, "animations", || {
                format!("{} animations", doc.animations().count())
            });
    }
    scene.warnings.extend(importer.unsupported.warnings(label));
    if scene.instances.is_empty() {
        let skipped = if scene.warnings.is_empty() {
            String::new()
        } else {
            format!(" ({})", scene.warnings.join("; "))
        };
        return Err(format!(
            "scene {} is empty: it places no triangle mesh{skipped}",
            gscene.index()
        ));
    }
    if !importer.camera_found {
        scene.camera = Camera::framing(&scene.bounds(), DEFAULT_VFOV_DEGREES);
        scene.notes.push(format!(
            "no camera in {label}: framing the scene's bounds from a three-quarter view"
        ));
    }
    if !scene.has_light() {
        scene.environment = Environment::NEUTRAL_SKY;
        scene.notes.push(format!(
            "no light in {label}: lighting it with a neutral default sky"
        ));
    }
    scene.validate().map_err(|e| e.to_string())?;
    Ok(scene)
}
