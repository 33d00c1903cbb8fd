//! BDPT's cached light vertices carry their base colour, the texture's and vertex colour's applied
//! by the light pass (`LVC_COLORS` in `shaders/bdpt/bdpt.glsl`), so that the camera pass's
//! connections need no texture lookups: a floor coloured by a texture renders as the same floor
//! coloured by its material's factor. The camera, between a reflecting emitter and the floor, sees
//! the floor; the paths that bounce from the floor to the emitter's underside and back connect
//! there to light vertices on the floor, whose colour then comes from the cache. With the same
//! random numbers the two renders trace the same paths: measured on lavapipe, their channel means
//! differ by 8.7e-6 at most (relative; the texel is stored in other precisions than the factor),
//! and by 3.9% when the camera pass ignores the cached colour (checked once).

use lucid_engine::capture::srgb_decode;
use lucid_engine::scene::Scene;
use lucid_passes::renderer::Algorithm;
use lucid_tests::gltf::{uv_plane, Doc, TopView};
use lucid_tests::render::render_once;
use lucid_tests::same_paths::difference;

const VIEW: TopView = TopView {
    height: 0.5,
    yfov: 1.6,
    size: 32,
};

/// The floor's colour, sRGB-encoded as a texel.
const TEXEL: [u8; 4] = [255, 128, 64, 255];

/// The floor under a reflecting 2 m square emitter 1 m above it facing down, the floor's base
/// colour from a one-texel texture when `textured`, else from its factor.
fn room(textured: bool) -> Scene {
    let mut doc = Doc::new();
    doc.uses("KHR_materials_emissive_strength");
    let colour = if textured {
        format!(
            r#""baseColorTexture": {{"index": {}}}"#,
            doc.texture(1, 1, &[TEXEL], None)
        )
    } else {
        let [r, g, b] = [0, 1, 2].map(|c| srgb_decode(f32::from(TEXEL[c]) / 255.0));
        format!(r#""baseColorFactor": [{r}, {g}, {b}, 1]"#)
    };
    let floor = doc.material(&format!(
        r#"{{"pbrMetallicRoughness": {{{colour}, "metallicFactor": 0}}}}"#
    ));
    let emitter = doc.material(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0},
            "emissiveFactor": [1, 1, 1],
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}"#,
    );
    uv_plane(&mut doc, 1.0, 0.0, false, floor, &[]);
    uv_plane(&mut doc, 1.0, 1.0, true, emitter, &[]);
    VIEW.add_to(&mut doc);
    doc.load("room.gltf")
}

#[test]
fn cached_light_vertices_keep_their_texture_colour() {
    let textured = room(true);
    assert!(textured.features().textures, "{}", textured.features());
    assert!(!room(false).features().textures);
    let render = |scene| render_once(scene, Algorithm::Bidirectional, 4, 5, VIEW.size);
    let (a, b) = (render(textured), render(room(false)));
    let d = difference(&a, &b);
    eprintln!("textured against plain floor: {d:?}");
    assert!(
        d.mean < 1e-4,
        "the texture's colour is not what the cache connects to: {d:?}"
    );
}
