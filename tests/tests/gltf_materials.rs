//! glTF metallic-roughness materials: a metal's metallic-roughness texture sets metal and
//! roughness per texel (roughness in G, metal in B), rendered on lavapipe.

use glam::Vec3;
use lucid_engine::capture::ImageData;
use lucid_engine::scene::Scene;
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::gltf::{plane, Doc};
use lucid_tests::render::render_accumulated;

/// A 2x1 PNG: a smooth metal texel (G 0, B 255), then a rough non-metal one (G 255, B 0).
const METAL_THEN_DIFFUSE: &str =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAYAAAD0In+KAAAAD0lEQVR4nGNgYPj/nwEIAQ76A/2ILbfFAAAAAElFTkSuQmCC";

const SIZE: u32 = 64;

/// A 2 m floor (u along x) of `material` under a 1000 cd point light, seen from straight above.
fn floor(material: &str) -> Scene {
    let mut doc = Doc::new();
    let (positions, indices) = plane(1.0);
    let uvs: Vec<[f32; 2]> = positions
        .iter()
        .map(|p| [(p[0] + 1.0) / 2.0, (p[2] + 1.0) / 2.0])
        .collect();
    let p = doc.floats(&positions);
    let t = doc.floats(&uvs);
    let i = doc.indices(&indices);
    doc.member(&format!(
        r#""images": [{{"uri": "data:image/png;base64,{METAL_THEN_DIFFUSE}"}}],
  "textures": [{{"source": 0}}]"#
    ));
    let m = doc.material(material);
    let mesh = doc.mesh(&[("POSITION", p), ("TEXCOORD_0", t)], Some(i), Some(m));
    doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
    doc.light(
        r#"{"type": "point", "intensity": 1000}"#,
        r#""translation": [0, 1, 0]"#,
    );
    let q = glam::Quat::from_rotation_arc(Vec3::NEG_Z, Vec3::NEG_Y);
    doc.camera(
        1.2,
        &format!(
            r#""rotation": [{}, {}, {}, {}], "translation": [0, 2, 0]"#,
            q.x, q.y, q.z, q.w
        ),
    );
    doc.load("floor.gltf")
}

fn render(scene: Scene) -> ImageData {
    render_accumulated(
        scene,
        (SIZE, SIZE),
        Settings {
            algorithm: Algorithm::PathTracing,
            samples_per_pixel: SamplesPerPixel::new(4).unwrap(),
            max_depth: 3,
            ..Settings::default()
        },
        1,
    )
}

/// Luminance-free brightness (green) of the floor at world x (z = 0).
fn at(image: &ImageData, x: f32) -> f32 {
    let ndc = x / (2.0 * 0.6f32.tan());
    let column = ((ndc + 1.0) / 2.0 * SIZE as f32) as u32;
    image.get(column, SIZE / 2).unwrap()[1]
}

#[test]
fn a_metallic_roughness_texture_sets_metal_and_roughness_per_texel() {
    let textured = floor(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
            "metallicRoughnessTexture": {"index": 0}}}"#,
    );
    let m = &textured.materials[0];
    assert_eq!(m.metallic_roughness_texture.map(|t| t.texture), Some(0));
    assert!(!textured.textures[0].srgb, "data, not colour");
    let f = textured.features();
    assert!(f.conductor && f.diffuse && f.textures, "{f}");
    assert!(textured.warnings.is_empty(), "{:?}", textured.warnings);
    let image = render(textured);
    let (metal, diffuse) = (at(&image, -0.5), at(&image, 0.5));
    println!("textured: smooth metal texel {metal}, diffuse texel {diffuse}");
    // The smooth metal mirrors the black background; the diffuse texel is lit by the light.
    assert!(metal < 1e-3, "{metal}");
    assert!(diffuse > 0.05, "{diffuse}");
    // Without the texture the same material is rough metal everywhere: both halves reflect
    // some light, equally by symmetry.
    let plain = render(floor(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}}"#,
    ));
    let (left, right) = (at(&plain, -0.5), at(&plain, 0.5));
    println!("untextured rough metal: {left}, {right}");
    assert!(left > 0.005 && right > 0.005, "{left} {right}");
    // A material below half metal never uses the texture: all diffuse, no texture needed.
    let dielectric = floor(
        r#"{"pbrMetallicRoughness": {"metallicFactor": 0.2, "metallicRoughnessTexture": {"index": 0}}}"#,
    );
    assert_eq!(dielectric.materials[0].metallic_roughness_texture, None);
}
