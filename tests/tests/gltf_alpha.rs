//! glTF cut-outs: `alphaMode: MASK` lets primary and shadow rays through where base alpha x
//! texture alpha x vertex alpha is below `alphaCutoff`; `BLEND` is stochastic transparency (a ray
//! meets the surface with probability equal to the opacity).

use glam::Vec3;
use lucid_engine::scene::Scene;
use lucid_passes::renderer::Algorithm;
use lucid_tests::gltf::{uv_plane, Doc, TopView};
use lucid_tests::render::{gbuffer_once, mean_at, render_once};

const SIZE: u32 = 32;

/// A 4x4 checkerboard of 2x2 blocks: opaque top-left and bottom-right, clear elsewhere (blocks
/// of 2 keep bilinear filtering from blurring the quadrants' insides).
fn checkerboard() -> Vec<[u8; 4]> {
    (0..16)
        .map(|i| {
            let (x, y) = (i % 4 / 2, i / 4 / 2);
            [255, 255, 255, if x == y { 255 } else { 0 }]
        })
        .collect()
}

/// A red floor, a green 2 m square `panel` material (its JSON members) 1 m above it, a sun
/// straight above, and `view`.
fn scene(panel: &str, checker: bool, vertex_alpha: Option<u8>, view: TopView) -> Scene {
    let mut doc = Doc::new();
    let red = doc.material(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0, 0, 1], "metallicFactor": 0}}"#,
    );
    let texture = if checker {
        format!(
            r#", "baseColorTexture": {{"index": {}}}"#,
            doc.texture(4, 4, &checkerboard(), None)
        )
    } else {
        String::new()
    };
    let green = doc.material(&format!(
        r#"{{"pbrMetallicRoughness": {{"baseColorFactor": [0, 0.8, 0, {}], "metallicFactor": 0{texture}}}{panel}}}"#,
        if panel.contains("BLEND") && !checker { "0.5" } else { "1" }
    ));
    uv_plane(&mut doc, 1.0, 0.0, false, red, &[]);
    let colors = vertex_alpha.map(|a| doc.unorm8(&[[255u8, 255, 255, a]; 4]));
    let extra: Vec<(&str, usize)> = colors.map(|c| ("COLOR_0", c)).into_iter().collect();
    uv_plane(&mut doc, 1.0, 1.0, false, green, &extra);
    let q = glam::Quat::from_rotation_arc(Vec3::NEG_Z, Vec3::NEG_Y);
    doc.light(
        r#"{"type": "directional", "intensity": 1000}"#,
        &format!(r#""rotation": [{}, {}, {}, {}]"#, q.x, q.y, q.z, q.w),
    );
    view.add_to(&mut doc);
    doc.load("cut-out.gltf")
}

/// Seen from above the panel.
const ABOVE: TopView = TopView {
    height: 2.0,
    yfov: 0.6,
    size: SIZE,
};

/// Seen from between the panel and the floor: the floor and the panel's shadow only.
const BELOW: TopView = TopView {
    height: 0.5,
    yfov: 1.2,
    size: SIZE,
};

/// Opaque (u < 0.5, v < 0.5 and u > 0.5, v > 0.5) and clear quadrants of the panel's texture as
/// floor regions, kept away from the seams.
fn quadrants(view: &TopView) -> [Vec<(u32, u32)>; 2] {
    let near = [-1.0, -0.1];
    let far = [0.1, 1.0];
    let mut opaque = view.pixels_in(near, near);
    opaque.extend(view.pixels_in(far, far));
    let mut clear = view.pixels_in(far, near);
    clear.extend(view.pixels_in(near, far));
    [opaque, clear]
}

#[test]
fn a_mask_shows_the_floor_through_the_cut_outs() {
    let masked = scene(r#", "alphaMode": "MASK""#, true, None, ABOVE);
    assert!(masked.features().alpha_test, "{}", masked.features());
    assert!(masked.warnings.is_empty(), "{:?}", masked.warnings);
    let [opaque, clear] = quadrants(&ABOVE);
    let [albedo, _] = gbuffer_once(masked, SIZE);
    let (red_clear, green_clear) = (mean_at(&albedo, &clear, 0), mean_at(&albedo, &clear, 1));
    let (red_opaque, green_opaque) = (mean_at(&albedo, &opaque, 0), mean_at(&albedo, &opaque, 1));
    println!(
        "clear: red {red_clear} green {green_clear}; opaque: red {red_opaque} green {green_opaque}"
    );
    assert!(
        red_clear > 0.7 && green_clear < 0.05,
        "the floor through the cut-outs"
    );
    assert!(
        green_opaque > 0.7 && red_opaque < 0.05,
        "the panel elsewhere"
    );
    // Opaque, the same file shows the panel everywhere.
    let [albedo, _] = gbuffer_once(scene("", true, None, ABOVE), SIZE);
    assert!(mean_at(&albedo, &clear, 1) > 0.7);
    // A cutoff above the texels' alpha removes the whole panel; vertex alpha below it too.
    let [albedo, _] = gbuffer_once(
        scene(
            r#", "alphaMode": "MASK", "alphaCutoff": 1.01"#,
            true,
            None,
            ABOVE,
        ),
        SIZE,
    );
    assert!(mean_at(&albedo, &opaque, 0) > 0.7);
    let [albedo, _] = gbuffer_once(
        scene(r#", "alphaMode": "MASK""#, true, Some(100), ABOVE),
        SIZE,
    );
    assert!(mean_at(&albedo, &opaque, 0) > 0.7, "vertex alpha 0.4 < 0.5");
}

#[test]
fn a_mask_casts_a_checkered_shadow() {
    let [opaque, clear] = quadrants(&BELOW);
    let render = |panel: &str| {
        render_once(
            scene(panel, true, None, BELOW),
            Algorithm::PathTracing,
            1,
            2,
            SIZE,
        )
    };
    let masked = render(r#", "alphaMode": "MASK""#);
    let (lit, shadowed) = (mean_at(&masked, &clear, 0), mean_at(&masked, &opaque, 0));
    println!("under the cut-outs {lit}, under the opaque texels {shadowed}");
    assert!(lit > 0.2 && shadowed < 0.01 * lit, "{lit} {shadowed}");
    let opaque_panel = render("");
    assert!(
        mean_at(&opaque_panel, &clear, 0) < 0.01 * lit,
        "no light through an opaque panel"
    );
}

#[test]
fn blending_lets_through_one_minus_the_opacity_on_average() {
    let all = BELOW.pixels_in([-1.0, 1.0], [-1.0, 1.0]);
    let render = |panel: &str, algorithm| {
        let image = render_once(scene(panel, false, None, BELOW), algorithm, 64, 2, SIZE);
        mean_at(&image, &all, 0)
    };
    for algorithm in [Algorithm::PathTracing, Algorithm::Bidirectional] {
        let half = render(r#", "alphaMode": "BLEND""#, algorithm);
        let open = render(r#", "alphaMode": "MASK", "alphaCutoff": 1.01"#, algorithm);
        println!("{algorithm:?}: behind a half-opaque panel {half}, no panel {open}");
        assert!((half / open - 0.5).abs() < 0.05, "{half} vs {open}");
    }
}
