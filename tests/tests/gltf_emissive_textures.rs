//! glTF emissive textures: emission varies per texel, and light sampling stays unbiased (a
//! half-black emissive texture lights a room half as much as a white one, with path tracing and
//! BDPT alike).

use lucid_engine::capture::ImageData;
use lucid_engine::scene::Scene;
use lucid_passes::renderer::Algorithm;
use lucid_tests::gltf::{uv_plane, Doc, TopView};
use lucid_tests::render::{mean_at, render_once};

/// The camera, between the emitter and the floor, sees the floor only.
const VIEW: TopView = TopView {
    height: 0.5,
    yfov: 1.6,
    size: 32,
};

const WHITE: [u8; 4] = [255, 255, 255, 255];
const BLACK: [u8; 4] = [0, 0, 0, 255];

/// A white floor under a 2 m square emitter 1 m above it facing down, emitting factor x
/// strength 4 times the 2x1 emissive texture `texels` (u along +x) when given.
fn room(texels: Option<[[u8; 4]; 2]>) -> Scene {
    let mut doc = Doc::new();
    doc.uses("KHR_materials_emissive_strength");
    let floor = doc.material(r#"{"pbrMetallicRoughness": {"metallicFactor": 0}}"#);
    let texture = texels.map_or(String::new(), |t| {
        format!(
            r#", "emissiveTexture": {{"index": {}}}"#,
            doc.texture(2, 1, &t, None)
        )
    });
    let emitter = doc.material(&format!(
        r#"{{"pbrMetallicRoughness": {{"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
            "emissiveFactor": [1, 1, 1]{texture},
            "extensions": {{"KHR_materials_emissive_strength": {{"emissiveStrength": 4}}}}}}"#
    ));
    uv_plane(&mut doc, 1.0, 0.0, false, floor, &[]);
    uv_plane(&mut doc, 1.0, 1.0, true, emitter, &[]);
    VIEW.add_to(&mut doc);
    doc.load("room.gltf")
}

fn render(scene: Scene, algorithm: Algorithm) -> ImageData {
    render_once(scene, algorithm, 64, 2, VIEW.size)
}

#[test]
fn a_half_black_emissive_texture_gives_half_the_light() {
    let half = room(Some([WHITE, BLACK]));
    assert!(half.features().emissive_textures, "{}", half.features());
    assert!(half.warnings.is_empty(), "{:?}", half.warnings);
    assert!(!room(None).features().emissive_textures);
    let all = VIEW.pixels_in([-2.0, 2.0], [-2.0, 2.0]);
    let left = VIEW.pixels_in([-2.0, -0.2], [-2.0, 2.0]);
    let right = VIEW.pixels_in([0.2, 2.0], [-2.0, 2.0]);
    for algorithm in [Algorithm::PathTracing, Algorithm::Bidirectional] {
        let plain = mean_at(&render(room(None), algorithm), &all, 0);
        let white = mean_at(&render(room(Some([WHITE, WHITE])), algorithm), &all, 0);
        let image = render(half.clone(), algorithm);
        let half_lit = mean_at(&image, &all, 0);
        let (l, r) = (mean_at(&image, &left, 0), mean_at(&image, &right, 0));
        println!("{algorithm:?}: no texture {plain}, white {white}, half black {half_lit} (left {l}, right {r})");
        // A white texture changes nothing; half the texels black, half the light.
        assert!((white / plain - 1.0).abs() < 0.05, "{white} vs {plain}");
        assert!(
            (half_lit / white - 0.5).abs() < 0.05,
            "{half_lit} vs {white}"
        );
        // The light comes from the white half (over x < 0).
        assert!(l > 1.3 * r, "left {l}, right {r}");
    }
}
