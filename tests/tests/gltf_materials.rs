//! glTF metallic-roughness materials: the metallic-roughness texture sets metal and roughness per
//! texel (roughness in G, metal in B, scaling the factors), a metallic factor between 0 and 1 mixes
//! metal and dielectric, and `KHR_materials_specular` sets the dielectric's specular layer;
//! rendered on lavapipe. (The model itself is checked against a CPU integration in
//! `ggx_furnace.rs`.)

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
    assert!(f.metal_rough && f.textures && !f.conductor, "{f}");
    assert!(textured.warnings.is_empty(), "{:?}", textured.warnings);
    let image = render(textured);
    let (metal, dielectric) = (at(&image, -0.5), at(&image, 0.5));
    println!("textured: smooth metal texel {metal}, rough dielectric texel {dielectric}");
    // The smooth metal mirrors the black background; the dielectric's diffuse is lit by the light.
    // (The pixel's samples reach a little past the texel's centre, where bilinear filtering mixes
    // in up to a few percent of the dielectric texel.)
    assert!(dielectric > 0.05, "{dielectric}");
    assert!(metal < 0.03 * dielectric, "{metal}");
    // Without the texture the same material is rough metal everywhere: both halves reflect
    // some light, equally by symmetry.
    let plain = render(floor(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}}"#,
    ));
    let (left, right) = (at(&plain, -0.5), at(&plain, 0.5));
    println!("untextured rough metal: {left}, {right}");
    assert!(left > 0.005 && right > 0.005, "{left} {right}");
}

#[test]
fn a_partial_metallic_factor_mixes_metal_and_dielectric() {
    // Metallic 0.2 times the texture's B: the left texel is a fifth smooth metal (mirroring the
    // black background) and four fifths dielectric, the right texel all dielectric; so the left
    // shows about 80% of the right's diffuse light (less the right's rough specular share).
    let scene = floor(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0.2,
            "metallicRoughnessTexture": {"index": 0}}}"#,
    );
    assert_eq!(scene.materials[0].metallic, 0.2);
    let image = render(scene);
    let (mixed, dielectric) = (at(&image, -0.5), at(&image, 0.5));
    let ratio = mixed / dielectric;
    println!("metallic 0.2: {mixed}, metallic 0: {dielectric}, ratio {ratio}");
    assert!((0.72..0.88).contains(&ratio), "{ratio}");
}

#[test]
fn the_specular_extension_scales_the_dielectric_layer() {
    // A black rough dielectric shows its specular layer alone: none with specularFactor 0, more
    // with a higher IOR (F0 0.04 at 1.5, 0.11 at 2), and tinted by specularColorFactor.
    let black = |extensions: &str| {
        let scene = floor(&format!(
            r#"{{"pbrMetallicRoughness": {{"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0,
                "roughnessFactor": 0.5}}, "extensions": {{{extensions}}}}}"#
        ));
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
        let image = render(scene);
        image.get(SIZE / 2, SIZE / 2).unwrap()
    };
    let none = black(r#""KHR_materials_specular": {"specularFactor": 0}"#);
    let default = black("");
    let dense = black(r#""KHR_materials_ior": {"ior": 2}"#);
    let red = black(r#""KHR_materials_specular": {"specularColorFactor": [1, 0, 0]}"#);
    println!("specular 0 {none:?}, default {default:?}, ior 2 {dense:?}, red {red:?}");
    assert_eq!(none[1], 0.0);
    assert!(default[1] > 0.01, "{default:?}");
    let ratio = dense[1] / default[1];
    assert!((2.2..3.6).contains(&ratio), "ior 2 / ior 1.5: {ratio}");
    assert!(
        red[0] > 0.9 * default[0] && red[1] < 0.2 * default[1],
        "{red:?}"
    );
}
