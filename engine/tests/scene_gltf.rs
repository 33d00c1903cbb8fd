//! glTF import: every material kind, textures, cameras, lights, GLB, and
//! one broken file of each kind (written to a temporary directory).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

use glam::{UVec3, Vec3};
use lucid_engine::scene::{
    load_gltf, load_gltf_slice, Camera, Environment, MaterialKind, PunctualLight, SceneError,
    TexelData, LUMENS_PER_WATT,
};

static COUNTER: AtomicU32 = AtomicU32::new(0);

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "lucid-gltf-{tag}-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A unit quad: positions, normals, uvs (f32) and u16 indices: 140 bytes.
fn quad_bin() -> Vec<u8> {
    let f = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut b = f(&[-1., -1., 0., 1., -1., 0., 1., 1., 0., -1., 1., 0.]);
    b.extend(f(&[0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1.]));
    b.extend(f(&[0., 1., 1., 1., 1., 0., 0., 0.]));
    b.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    b
}

const QUAD_VIEWS: &str = r#""bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 48},
    {"buffer": 0, "byteOffset": 96, "byteLength": 32},
    {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]"#;

/// A document with one quad mesh per material, each on its own node,
/// plus `extra` top-level members (each followed by a comma).
fn quad_doc(buffer_uri: &str, materials: &[&str], extra: &str) -> String {
    let meshes: Vec<String> = (0..materials.len())
        .map(|i| format!(r#"{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}}, "indices": 3, "material": {i}}}]}}"#))
        .collect();
    let nodes: Vec<String> = (0..materials.len())
        .map(|i| format!(r#"{{"mesh": {i}, "translation": [{}, 0, 0]}}"#, 3 * i))
        .collect();
    let roots: Vec<String> = (0..materials.len()).map(|i| i.to_string()).collect();
    format!(
        r#"{{"asset": {{"version": "2.0"}}, {extra}
  "scene": 0, "scenes": [{{"nodes": [{}]}}],
  "nodes": [{}], "meshes": [{}], "materials": [{}],
  "buffers": [{{"byteLength": 140, "uri": "{buffer_uri}"}}],
  {QUAD_VIEWS}}}"#,
        roots.join(","),
        nodes.join(","),
        meshes.join(","),
        materials.join(",")
    )
}

const EMISSIVE: &str = r#"{"name": "lamp", "emissiveFactor": [1, 1, 1]}"#;

fn write_case(tag: &str, doc: &str, with_bin: bool) -> PathBuf {
    let dir = temp_dir(tag);
    if with_bin {
        std::fs::write(dir.join("quad.bin"), quad_bin()).unwrap();
    }
    let file = dir.join("scene.gltf");
    std::fs::write(&file, doc).unwrap();
    file
}

fn gltf_error(result: Result<lucid_engine::scene::Scene, SceneError>) -> (String, String) {
    match result {
        Err(SceneError::Gltf { file, message }) => (file, message),
        other => panic!("expected a glTF error, got {other:?}"),
    }
}

#[test]
fn imports_every_material_kind() {
    let materials = [
        r#"{"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.2, 0.1, 1], "metallicFactor": 0, "roughnessFactor": 1}}"#,
        r#"{"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.78, 0.34, 1], "metallicFactor": 1, "roughnessFactor": 0.5}}"#,
        r#"{"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0}, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.33}}}"#,
        r#"{"name": "frosted", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.6}, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.9}}}"#,
        r#"{"name": "lamp", "emissiveFactor": [1, 0.5, 0.25], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}"#,
    ];
    let extra = r#""extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"],
        "extensionsRequired": ["KHR_materials_transmission"],"#;
    let file = write_case("materials", &quad_doc("quad.bin", &materials, extra), true);
    let s = load_gltf(&file).unwrap();
    // Frosted glass transmits 90%: rendered as fully transmissive, and said so.
    match s.warnings.as_slice() {
        [w] => assert!(
            w.contains("partial transmission") && w.contains("material `frosted`"),
            "{w}"
        ),
        other => panic!("{other:?}"),
    }
    assert_eq!(s.meshes.len(), 5);
    assert_eq!(s.instances.len(), 5);
    let m = |n: &str| s.materials.iter().find(|m| m.name == n).unwrap().clone();
    // Not a pure metal: glTF's metallic-roughness model in full (specular layer over diffuse).
    assert_eq!(m("clay").kind, MaterialKind::MetalRough);
    assert_eq!(m("clay").metallic, 0.0);
    assert_eq!(m("clay").base_color, Vec3::new(0.7, 0.2, 0.1));
    assert_eq!(m("gold").kind, MaterialKind::Conductor);
    assert!((m("gold").alpha - 0.25).abs() < 1e-6);
    assert!(m("glass").is_smooth_dielectric() && (m("glass").ior - 1.33).abs() < 1e-6);
    assert!(m("frosted").is_rough_dielectric() && (m("frosted").ior - 1.5).abs() < 1e-6);
    assert_eq!(m("lamp").emission, Vec3::new(4.0, 2.0, 1.0));
    let f = s.features();
    assert!(
        f.metal_rough && f.conductor && f.dielectric_smooth && f.dielectric_rough && f.emissive
    );
    assert!(!f.diffuse, "glTF has no purely Lambertian material");
    assert_eq!(s.meshes[0].uvs.len(), 4);
    assert_eq!(
        s.instances[2].transform.translation,
        glam::Vec3A::new(6.0, 0.0, 0.0)
    );
}

#[test]
fn out_of_range_material_is_rejected_by_name() {
    let bad = r#"{"name": "negative-glass", "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 0.5}}}"#;
    let file = write_case("badior", &quad_doc("quad.bin", &[bad, EMISSIVE], ""), true);
    let (f, msg) = gltf_error(load_gltf(&file));
    assert!(f.ends_with("scene.gltf"));
    assert!(
        msg.contains("negative-glass") && msg.contains("below 1"),
        "{msg}"
    );
}

fn write_png(path: &Path) {
    let img = image::RgbaImage::from_fn(3, 2, |x, y| {
        image::Rgba([x as u8 * 100, y as u8 * 200, 7, 255])
    });
    img.save(path).unwrap();
}

#[test]
fn imports_textures_from_files_and_data_uris() {
    let dir = temp_dir("texture");
    write_png(&dir.join("albedo.png"));
    std::fs::write(dir.join("quad.bin"), quad_bin()).unwrap();
    let png = std::fs::read(dir.join("albedo.png")).unwrap();
    let materials = [
        r#"{"name": "file-tex", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}"#,
        r#"{"name": "uri-tex", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}}"#,
        EMISSIVE,
    ];
    let extra = format!(
        r#""textures": [{{"source": 0}}, {{"source": 1}}],
        "images": [{{"uri": "albedo.png"}}, {{"uri": "data:image/png;base64,{}"}}],"#,
        base64::encode(&png)
    );
    let file = dir.join("tex.gltf");
    std::fs::write(&file, quad_doc("quad.bin", &materials, &extra)).unwrap();
    let s = load_gltf(&file).unwrap();
    assert_eq!(s.textures.len(), 2);
    for t in &s.textures {
        assert_eq!((t.width, t.height), (3, 2));
        let TexelData::Rgba8(px) = &t.texels else {
            panic!("rgba8 expected")
        };
        assert_eq!(px[5], [200, 200, 7, 255]);
        assert!(t.srgb);
    }
    assert_eq!(
        s.materials[0].base_color_texture.map(|t| t.texture),
        Some(0)
    );
    assert!(s.features().textures);
}

#[test]
fn imports_cameras_hierarchy_instancing_and_punctual_lights() {
    let extra = r#""extensionsUsed": ["KHR_lights_punctual"],
      "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.5, 0.5], "intensity": 10},
        {"type": "spot", "intensity": 20, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}},
        {"type": "directional", "intensity": 2}]}},
      "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}}],"#;
    let doc = format!(
        r#"{{"asset": {{"version": "2.0"}}, {extra}
      "scene": 0, "scenes": [{{"nodes": [0, 3, 4, 5, 6]}}],
      "nodes": [
        {{"translation": [0, 2, 0], "children": [1, 2]}},
        {{"mesh": 0, "translation": [1, 0, 0]}},
        {{"mesh": 0, "scale": [2, 2, 2]}},
        {{"camera": 0, "translation": [0, 1, 10], "rotation": [0, 0.3826834, 0, 0.9238795]}},
        {{"translation": [0, 4, 0], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
        {{"rotation": [-0.7071068, 0, 0, 0.7071068], "translation": [0, 5, 0], "extensions": {{"KHR_lights_punctual": {{"light": 1}}}}}},
        {{"rotation": [-0.7071068, 0, 0, 0.7071068], "extensions": {{"KHR_lights_punctual": {{"light": 2}}}}}}],
      "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 3}}]}}],
      "buffers": [{{"byteLength": 140, "uri": "quad.bin"}}],
      {QUAD_VIEWS}}}"#
    );
    let file = write_case("nodes", &doc, true);
    let s = load_gltf(&file).unwrap();
    assert_eq!(s.meshes.len(), 1, "one mesh shared by two instances");
    assert_eq!(s.instances.len(), 2);
    assert_eq!(
        s.instances[0].transform.translation,
        glam::Vec3A::new(1.0, 2.0, 0.0)
    );
    let b = s.bounds();
    assert!(
        (b.min - Vec3::new(-2.0, 0.0, 0.0)).length() < 1e-6
            && (b.max - Vec3::new(2.0, 4.0, 0.0)).length() < 1e-6
    );
    // Camera: rotated 45° about +Y, so it looks along (-sin 45°, 0, -cos 45°).
    assert_eq!(s.camera.position, Vec3::new(0.0, 1.0, 10.0));
    assert!((s.camera.vfov - 0.7).abs() < 1e-6);
    let f = s.camera.forward();
    assert!(
        (f - Vec3::new(-0.70710677, 0.0, -0.70710677)).length() < 1e-5,
        "{f}"
    );
    // Normals were missing and are computed.
    assert!(s.meshes[0]
        .normals
        .iter()
        .all(|n| (*n - Vec3::Z).length() < 1e-6));
    match s.punctual_lights.as_slice() {
        [PunctualLight::Point {
            position,
            intensity,
        }, PunctualLight::Spot {
            direction,
            inner_angle,
            outer_angle,
            ..
        }] => {
            assert_eq!(*position, Vec3::new(0.0, 4.0, 0.0));
            // 10 cd of (1, 0.5, 0.5): W/sr through 683 lm/W.
            let want = Vec3::new(10.0, 5.0, 5.0) / LUMENS_PER_WATT;
            assert!((*intensity - want).length() < 1e-7, "{intensity}");
            assert!((*direction - Vec3::NEG_Y).length() < 1e-5, "{direction}");
            assert_eq!((*inner_angle, *outer_angle), (0.1, 0.5));
        }
        other => panic!("{other:?}"),
    }
    let sun = s.sun.unwrap();
    assert!((sun.direction - Vec3::Y).length() < 1e-5);
    assert_eq!(sun.irradiance, Vec3::splat(2.0 / LUMENS_PER_WATT), "2 lux");
    let f = s.features();
    assert!(f.delta_lights && f.sun && !f.emissive);
}

/// Packs a JSON document and an optional binary chunk into GLB bytes.
fn glb(json: &str, bin: Option<&[u8]>) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let mut b = bin.unwrap_or_default().to_vec();
    while b.len() % 4 != 0 {
        b.push(0);
    }
    let bin_chunk = if bin.is_some() { 8 + b.len() } else { 0 };
    let total = 12 + 8 + j.len() + bin_chunk;
    let mut out = Vec::new();
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((j.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(j);
    if bin.is_some() {
        out.extend((b.len() as u32).to_le_bytes());
        out.extend(0x004E_4942u32.to_le_bytes());
        out.extend(b);
    }
    out
}

#[test]
fn imports_glb_files() {
    let json = quad_doc("", &[EMISSIVE], "").replace(r#", "uri": """#, "");
    let bytes = glb(&json, Some(&quad_bin()));
    let dir = temp_dir("glb");
    let file = dir.join("quad.glb");
    std::fs::write(&file, &bytes).unwrap();
    let s = load_gltf(&file).unwrap();
    assert_eq!(s.triangle_count(), 2);
    // Truncated and wrong-version GLBs are errors, not panics.
    for cut in [3, 11, 20, bytes.len() - 1] {
        assert!(load_gltf_slice(&bytes[..cut], None, "cut.glb").is_err());
    }
    let mut v1 = bytes.clone();
    v1[4] = 1;
    assert!(gltf_error(load_gltf_slice(&v1, None, "v1.glb"))
        .1
        .contains("version"));
    let no_bin = glb(&json, None);
    let (_, msg) = gltf_error(load_gltf_slice(&no_bin, None, "nobin.glb"));
    assert!(msg.contains("binary chunk"), "{msg}");
}

#[test]
fn missing_buffer_is_an_error_naming_file_and_buffer() {
    let file = write_case("nobin", &quad_doc("quad.bin", &[EMISSIVE], ""), false);
    let (f, msg) = gltf_error(load_gltf(&file));
    assert!(f.ends_with("scene.gltf"), "{f}");
    assert!(
        msg.contains("buffer 0") && msg.contains("quad.bin"),
        "{msg}"
    );
    let short = write_case("shortbin", &quad_doc("quad.bin", &[EMISSIVE], ""), false);
    std::fs::write(short.with_file_name("quad.bin"), [0u8; 10]).unwrap();
    assert!(gltf_error(load_gltf(&short)).1.contains("byteLength"));
}

#[test]
fn missing_image_is_an_error() {
    let mat = r#"{"name": "tex", "emissiveFactor": [1, 1, 1], "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}"#;
    let extra = r#""textures": [{"source": 0}], "images": [{"uri": "nowhere.png"}],"#;
    let file = write_case("noimage", &quad_doc("quad.bin", &[mat], extra), true);
    let (_, msg) = gltf_error(load_gltf(&file));
    assert!(
        msg.contains("image 0") && msg.contains("nowhere.png"),
        "{msg}"
    );
    let corrupt = write_case("badimage", &quad_doc("quad.bin", &[mat], extra), true);
    std::fs::write(corrupt.with_file_name("nowhere.png"), b"not a png").unwrap();
    assert!(gltf_error(load_gltf(&corrupt)).1.contains("decode"));
}

#[test]
fn unsupported_required_extensions_are_named() {
    for ext in ["KHR_draco_mesh_compression", "EXT_meshopt_compression"] {
        let extra = format!(r#""extensionsUsed": ["{ext}"], "extensionsRequired": ["{ext}"],"#);
        let file = write_case("draco", &quad_doc("quad.bin", &[EMISSIVE], &extra), true);
        let (_, msg) = gltf_error(load_gltf(&file));
        assert!(msg.contains(ext) && msg.contains("not supported"), "{msg}");
    }
    let extra = r#""extensionsUsed": ["EXT_fancy"],"#;
    let file = write_case("used", &quad_doc("quad.bin", &[EMISSIVE], extra), true);
    let s = load_gltf(&file).unwrap();
    assert!(s.warnings.iter().any(|w| w.contains("EXT_fancy")));
}

#[test]
fn malformed_accessors_are_errors() {
    let base = quad_doc("quad.bin", &[EMISSIVE], "");
    let cases = [
        // Too many elements for the view.
        (
            r#""count": 4, "type": "VEC3", "min""#,
            r#""count": 400, "type": "VEC3", "min""#,
            "overrun",
        ),
        // View past the end of the buffer.
        (
            r#""byteOffset": 128, "byteLength": 12"#,
            r#""byteOffset": 136, "byteLength": 12"#,
            "outside buffer",
        ),
        // Wrong component type for positions.
        (
            r#""componentType": 5126, "count": 4, "type": "VEC3", "min""#,
            r#""componentType": 5123, "count": 4, "type": "VEC3", "min""#,
            "component type",
        ),
        // Indices not a multiple of three.
        (
            r#""count": 6, "type": "SCALAR""#,
            r#""count": 5, "type": "SCALAR""#,
            "whole triangles",
        ),
        // Accessor index out of range (caught by validation).
        (r#""indices": 3"#, r#""indices": 9"#, "invalid glTF"),
    ];
    for (from, to, needle) in cases {
        assert!(base.contains(from), "{from}");
        let file = write_case("accessor", &base.replacen(from, to, 1), true);
        let (_, msg) = gltf_error(load_gltf(&file));
        assert!(msg.contains(needle), "{needle}: {msg}");
    }
    // An index past the vertex count, and a NaN position.
    let mut bin = quad_bin();
    bin[128..130].copy_from_slice(&7u16.to_le_bytes());
    let file = write_case("badindex", &base, false);
    std::fs::write(file.with_file_name("quad.bin"), &bin).unwrap();
    assert!(gltf_error(load_gltf(&file)).1.contains("out of range"));
    let mut bin = quad_bin();
    bin[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
    let file = write_case("nan", &base, false);
    std::fs::write(file.with_file_name("quad.bin"), &bin).unwrap();
    assert!(gltf_error(load_gltf(&file)).1.contains("not finite"));
}

#[test]
fn empty_scenes_and_cycles_are_errors() {
    let empty = r#"{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"name": "nothing"}]}"#;
    let (_, msg) = gltf_error(load_gltf_slice(empty.as_bytes(), None, "empty.gltf"));
    assert!(msg.contains("empty"), "{msg}");
    let none = r#"{"asset": {"version": "2.0"}}"#;
    assert!(
        gltf_error(load_gltf_slice(none.as_bytes(), None, "none.gltf"))
            .1
            .contains("no scene")
    );
    let cycle = r#"{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"children": [1]}, {"children": [0]}]}"#;
    assert!(
        gltf_error(load_gltf_slice(cycle.as_bytes(), None, "cycle.gltf"))
            .1
            .contains("cycle")
    );
    let (_, msg) = gltf_error(load_gltf_slice(b"{not json", None, "junk.gltf"));
    assert!(msg.contains("JSON"), "{msg}");
    let (f, msg) = gltf_error(load_gltf(Path::new("/definitely/not/here.gltf")));
    assert!(
        f.contains("here.gltf") && msg.contains("cannot read"),
        "{msg}"
    );
}

#[test]
fn scene_without_light_or_camera_gets_the_neutral_sky_and_a_framing_camera_with_notes() {
    let dark =
        r#"{"name": "dark", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}"#;
    let file = write_case("nolight", &quad_doc("quad.bin", &[dark], ""), true);
    let s = load_gltf(&file).unwrap();
    assert!(s.has_light());
    assert!(s.punctual_lights.is_empty() && s.sun.is_none());
    assert_eq!(s.environment, Environment::NEUTRAL_SKY);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    let note = |what: &str| {
        s.notes
            .iter()
            .any(|n| n.contains(what) && n.contains("scene.gltf"))
    };
    assert!(note("no light") && note("sky"), "{:?}", s.notes);
    assert!(note("no camera") && note("three-quarter"), "{:?}", s.notes);
    assert_eq!(s.camera, Camera::framing(&s.bounds(), 45.0));
    // A file with a light keeps its black environment and says nothing about a sky.
    let lit = load_gltf(&write_case(
        "lit",
        &quad_doc("quad.bin", &[dark, EMISSIVE], ""),
        true,
    ))
    .unwrap();
    assert!(lit.environment.is_black());
    assert!(
        !lit.notes.iter().any(|n| n.contains("sky")),
        "{:?}",
        lit.notes
    );
}

#[test]
fn corpus_files_import() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/gltf");
    let tri = load_gltf(&dir.join("triangle_embedded.gltf")).unwrap();
    assert_eq!(tri.triangle_count(), 1);
    assert_eq!(tri.punctual_lights.len(), 1);
    let quad = load_gltf(&dir.join("quad_materials.gltf")).unwrap();
    assert_eq!(quad.instances.len(), 5);
    assert!(quad.sun.is_some() && quad.punctual_lights.len() == 1);
    let f = quad.features();
    assert!(
        f.conductor && f.dielectric_smooth && f.dielectric_rough && f.emissive && f.metal_rough
    );
    let tex = load_gltf(&dir.join("textured_quad.gltf")).unwrap();
    assert_eq!(tex.textures.len(), 1);
    assert_eq!((tex.textures[0].width, tex.textures[0].height), (2, 2));
}

#[test]
fn huge_geometry_is_reported_with_the_mesh_or_node_that_holds_it() {
    let base = quad_doc("quad.bin", &[EMISSIVE], "");
    let mut bin = quad_bin();
    bin[0..4].copy_from_slice(&3e38f32.to_le_bytes());
    let file = write_case("hugecoord", &base, false);
    std::fs::write(file.with_file_name("quad.bin"), &bin).unwrap();
    let (_, msg) = gltf_error(load_gltf(&file));
    assert!(
        msg.contains("mesh `mesh 0/0`")
            && msg.contains("POSITION 0")
            && msg.contains("out of range"),
        "{msg}"
    );
    let scaled = base.replace(
        r#"{"mesh": 0, "translation": [0, 0, 0]}"#,
        r#"{"mesh": 0, "name": "giant", "scale": [1e30, 1e30, 1e30]}"#,
    );
    assert_ne!(scaled, base);
    let (_, msg) = gltf_error(load_gltf(&write_case("hugescale", &scaled, true)));
    assert!(
        msg.contains("node 0 (`giant`)")
            && msg.contains("mesh `mesh 0/0`")
            && msg.contains("scale"),
        "{msg}"
    );
}

#[test]
fn strips_and_fans_are_triangulated() {
    let base = quad_doc("quad.bin", &[EMISSIVE], "");
    for (mode, expected) in [
        (5, [UVec3::new(0, 1, 2), UVec3::new(1, 3, 2)]),
        (6, [UVec3::new(1, 2, 0), UVec3::new(2, 3, 0)]),
    ] {
        let doc = base.replace(r#""indices": 3,"#, &format!(r#""mode": {mode},"#));
        let s = load_gltf(&write_case("strip", &doc, true)).unwrap();
        assert_eq!(s.meshes[0].indices, expected, "mode {mode}");
    }
    let lines = base.replace(r#""indices": 3,"#, r#""mode": 1,"#);
    let (_, msg) = gltf_error(load_gltf(&write_case("lines", &lines, true)));
    assert!(
        msg.contains("line primitives are not supported")
            && msg.contains("only triangles")
            && msg.contains("(Lines)"),
        "{msg}"
    );
}

#[test]
fn a_glb_that_is_not_binary_says_bad_magic() {
    let dir = temp_dir("notglb");
    let file = dir.join("scene.glb");
    std::fs::write(&file, quad_doc("quad.bin", &[EMISSIVE], "")).unwrap();
    let (_, msg) = gltf_error(load_gltf(&file));
    assert!(
        msg.contains("not a binary glTF") && msg.contains("bad magic"),
        "{msg}"
    );
}
