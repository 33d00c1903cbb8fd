//! What Lucid does not render of a glTF file is said once per feature per file, naming the file,
//! the feature, what is done instead and how many things use it, never dropped silently.

use lucid_tests::gltf::{plane, Doc};

/// A 1x1 PNG.
const PNG: &str = "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGM4kWL0HwAFtAJeHzr7ywAAAABJRU5ErkJggg==";

/// A file that uses every unsupported feature twice (and supported ones that used to warn).
fn everything_unsupported() -> Doc {
    let mut doc = Doc::new();
    doc.uses("KHR_materials_transmission");
    doc.uses("KHR_materials_specular");
    doc.uses("KHR_materials_clearcoat");
    let (positions, indices) = plane(1.0);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let times = doc.floats(&[[0.0f32], [1.0]]);
    let moves = doc.floats(&[[0.0f32, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    doc.member(&format!(
        r#""images": [{{"uri": "data:image/png;base64,{PNG}"}}],
  "samplers": [{{"wrapS": 33071, "wrapT": 10497}}],
  "textures": [{{"source": 0, "sampler": 0}}]"#
    ));
    let textured = |name: &str, alpha: &str| {
        format!(
            r#"{{"name": "{name}", "alphaMode": "{alpha}", "alphaCutoff": 0.5,
            "pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0, "texCoord": 1}},
                "metallicRoughnessTexture": {{"index": 0}}, "metallicFactor": 0.3}},
            "normalTexture": {{"index": 0}}, "occlusionTexture": {{"index": 0}},
            "emissiveTexture": {{"index": 0}}, "emissiveFactor": [1, 1, 1],
            "extensions": {{"KHR_materials_specular": {{"specularColorTexture": {{"index": 0}}}}}}}}"#
        )
    };
    let glass = |name: &str| {
        format!(
            r#"{{"name": "{name}", "pbrMetallicRoughness": {{"metallicRoughnessTexture": {{"index": 0}}}},
                "extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 0.5}}}}}}"#
        )
    };
    let materials = [
        doc.material(&textured("leaves", "MASK")),
        doc.material(&textured("glass-pane", "BLEND")),
        doc.material(&textured("fence", "MASK")),
        doc.material(&textured("window", "BLEND")),
        doc.material(&glass("bottle")),
        doc.material(&glass("vase")),
    ];
    for m in materials {
        let mesh = doc.mesh_json(&format!(
            r#"{{"primitives": [{{"attributes": {{"POSITION": {p}, "TEXCOORD_1": {p}}}, "indices": {i},
                "material": {m}, "targets": [{{"POSITION": {p}}}]}}]}}"#
        ));
        doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
    }
    for mode in [0, 1] {
        let mesh = doc.mesh_json(&format!(
            r#"{{"name": "wire-{mode}", "primitives": [{{"attributes": {{"POSITION": {p}}}, "mode": {mode}}}]}}"#
        ));
        doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
    }
    let skinned = doc.node(r#"{"mesh": 0, "skin": 0}"#);
    doc.node(r#"{"mesh": 1, "skin": 0}"#);
    doc.member(&format!(r#""skins": [{{"joints": [{skinned}]}}]"#));
    doc.member(&format!(
        r#""animations": [{{"channels": [{{"sampler": 0, "target": {{"node": 0, "path": "translation"}}}}],
            "samplers": [{{"input": {times}, "output": {moves}}}]}},
          {{"channels": [{{"sampler": 0, "target": {{"node": 1, "path": "translation"}}}}],
            "samplers": [{{"input": {times}, "output": {moves}}}]}}]"#
    ));
    for _ in 0..3 {
        doc.light(r#"{"type": "directional", "intensity": 1000}"#, "");
    }
    for _ in 0..2 {
        doc.light(r#"{"type": "point", "intensity": 100, "range": 5}"#, "");
        doc.camera_json(
            r#"{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "zfar": 10, "znear": 0.1}}"#,
            "",
        );
    }
    doc
}

#[test]
fn every_unsupported_feature_is_said_once_per_file() {
    let scene = everything_unsupported().load("kitchen-sink.gltf");
    for w in &scene.warnings {
        println!("{w}");
    }
    // (what the warning names, how many things use it)
    let expected = [
        (
            "metallic-roughness textures",
            "2 materials, the first material `bottle`",
        ),
        (
            "KHR_materials_specular textures",
            "4 materials, the first material `leaves`",
        ),
        (
            "partial transmission",
            "2 materials, the first material `bottle`",
        ),
        ("other than TEXCOORD_0", "4 materials"),
        (
            "point and line primitives",
            "2 primitives, the first mesh `wire-0/0` (Points)",
        ),
        ("morph targets", "6 primitives"),
        ("skins", "2 nodes"),
        ("animations", "2 animations"),
        ("orthographic cameras", "2 cameras"),
        ("only one directional light", "2 lights"),
        ("light ranges", "2 lights"),
        ("extension `KHR_materials_clearcoat`", ""),
    ];
    for (feature, users) in expected {
        let hits: Vec<&String> = scene
            .warnings
            .iter()
            .filter(|w| w.contains(feature))
            .collect();
        assert_eq!(hits.len(), 1, "{feature}: {:?}", scene.warnings);
        assert!(hits[0].starts_with("kitchen-sink.gltf: "), "{}", hits[0]);
        assert!(hits[0].contains(users), "{feature}: {}", hits[0]);
    }
    assert_eq!(scene.warnings.len(), expected.len(), "{:?}", scene.warnings);
}

#[test]
fn a_file_lucid_renders_whole_has_no_warning() {
    let mut doc = Doc::new();
    doc.uses("KHR_texture_transform");
    let (positions, indices) = plane(1.0);
    let p = doc.floats(&positions);
    let t = doc.floats(&[[0.0f32, 0.0]; 4]);
    let i = doc.indices(&indices);
    let texture = doc.texture(
        1,
        1,
        &[[128, 128, 255, 255]],
        Some(r#"{"wrapS": 33071, "wrapT": 33648}"#),
    );
    // Every texture slot, alpha modes and texture transforms are rendered.
    let transform =
        r#""extensions": {"KHR_texture_transform": {"offset": [0.5, 0], "scale": [2, 2]}}"#;
    let m = doc.material(&format!(
        r#"{{"alphaMode": "MASK", "alphaCutoff": 0.3, "emissiveFactor": [1, 1, 1],
            "pbrMetallicRoughness": {{"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0,
                "baseColorTexture": {{"index": {texture}, {transform}}}}},
            "normalTexture": {{"index": {texture}, "scale": 0.5, {transform}}},
            "occlusionTexture": {{"index": {texture}, "strength": 0.5}},
            "emissiveTexture": {{"index": {texture}}}}}"#
    ));
    let mesh = doc.mesh(&[("POSITION", p), ("TEXCOORD_0", t)], Some(i), Some(m));
    doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
    doc.light(
        r#"{"type": "point", "intensity": 100}"#,
        r#""translation": [0, 1, 0]"#,
    );
    let scene = doc.load("plain.gltf");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let m = &scene.materials[0];
    let slots = [
        m.base_color_texture,
        m.normal_texture,
        m.occlusion_texture,
        m.emissive_texture,
    ];
    assert!(slots.iter().all(Option::is_some), "{m:?}");
    let f = scene.features();
    assert!(
        f.normal_maps && f.emissive_textures && f.alpha_test && f.occlusion && f.texture_transforms,
        "{f}"
    );
}
