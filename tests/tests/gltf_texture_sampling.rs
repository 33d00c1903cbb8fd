//! How glTF textures are looked up: `KHR_texture_transform` (offset, rotation, scale) and the
//! sampler's wrap modes on every slot, and the occlusion texture, which darkens the G-buffer's
//! (and so the denoisers') albedo but never the light transport.

use glam::Vec2;
use lucid_engine::scene::{Scene, UvTransform};
use lucid_passes::renderer::Algorithm;
use lucid_tests::gltf::{uv_plane, Doc, TopView};
use lucid_tests::render::{gbuffer_once, mean_at, render_once};

const VIEW: TopView = TopView {
    height: 1.0,
    yfov: 1.6,
    size: 32,
};

/// The colours of an 8x8 texture's four 4x4 quadrants: red top-left, green top-right, blue
/// bottom-left, white bottom-right.
const QUADRANTS: [[u8; 4]; 4] = [
    [255, 0, 0, 255],
    [0, 255, 0, 255],
    [0, 0, 255, 255],
    [255, 255, 255, 255],
];

fn quadrant_texels() -> Vec<[u8; 4]> {
    (0..64)
        .map(|i| QUADRANTS[(i % 8 / 4) + 2 * (i / 8 / 4)])
        .collect()
}

/// A floor (u along +x, v along +z, 0 to 1 over [-1, 1]) whose base colour is the quadrant
/// texture, sampled with `sampler` and the texture info's extra JSON `info` members.
fn floor(sampler: Option<&str>, info: &str) -> Scene {
    let mut doc = Doc::new();
    doc.uses("KHR_texture_transform");
    let t = doc.texture(8, 8, &quadrant_texels(), sampler);
    let m = doc.material(&format!(
        r#"{{"pbrMetallicRoughness": {{"metallicFactor": 0,
            "baseColorTexture": {{"index": {t}{info}}}}}}}"#
    ));
    uv_plane(&mut doc, 1.0, 0.0, false, m, &[]);
    doc.light(
        r#"{"type": "point", "intensity": 10}"#,
        r#""translation": [0, 1, 0]"#,
    );
    VIEW.add_to(&mut doc);
    doc.load("sampled.gltf")
}

/// The quadrant colour (as linear 0/1 RGB) a lookup at `uv` lands in, wrapping by `wrap`.
fn expected(uv: Vec2, wrap: fn(f32) -> f32) -> [f32; 3] {
    let q = |x: f32| (wrap(x) * 2.0).floor().clamp(0.0, 1.0) as usize;
    QUADRANTS[q(uv.x) + 2 * q(uv.y)].map(|c| f32::from(c) / 255.0)[..3]
        .try_into()
        .unwrap()
}

fn repeat(x: f32) -> f32 {
    x - x.floor()
}

fn clamp(x: f32) -> f32 {
    x.clamp(0.0, 0.999)
}

fn mirror(x: f32) -> f32 {
    let k = x.rem_euclid(2.0);
    if k < 1.0 {
        k
    } else {
        2.0 - k
    }
}

/// Checks the G-buffer albedo of `scene` against `transform` and `wrap` at every pixel whose
/// lookup lies well inside a quadrant (bilinear filtering blurs the seams); returns how many.
fn check(scene: Scene, transform: UvTransform, wrap: fn(f32) -> f32) -> usize {
    let [albedo, _] = gbuffer_once(scene, VIEW.size);
    let mut checked = 0;
    for row in 0..VIEW.size {
        for column in 0..VIEW.size {
            let [x, z] = VIEW.floor_point(column, row);
            let uv = transform.apply(Vec2::new((x + 1.0) / 2.0, (z + 1.0) / 2.0));
            let inside = |c: f32| {
                let f = (wrap(c) * 2.0).fract();
                (0.15..0.85).contains(&f)
            };
            if !(inside(uv.x) && inside(uv.y)) {
                continue;
            }
            let got = albedo.get(column, row).unwrap();
            let want = expected(uv, wrap);
            for k in 0..3 {
                assert!(
                    (got[k] - want[k]).abs() < 0.05,
                    "pixel ({column}, {row}) at uv {uv}: {got:?}, want {want:?}"
                );
            }
            checked += 1;
        }
    }
    checked
}

#[test]
fn texture_transforms_move_the_texture_as_the_extension_says() {
    let plain = floor(None, "");
    assert!(!plain.features().texture_transforms);
    assert!(check(plain, UvTransform::IDENTITY, repeat) > 200);
    let transform = UvTransform {
        offset: Vec2::new(0.2, 0.1),
        rotation: 0.5,
        scale: Vec2::new(1.5, 0.8),
    };
    let moved = floor(
        None,
        r#", "extensions": {"KHR_texture_transform": {"offset": [0.2, 0.1], "rotation": 0.5,
            "scale": [1.5, 0.8]}}"#,
    );
    assert!(moved.features().texture_transforms, "{}", moved.features());
    assert!(moved.warnings.is_empty(), "{:?}", moved.warnings);
    assert!(check(moved, transform, repeat) > 100);
}

#[test]
fn wrap_modes_clamp_repeat_and_mirror() {
    let transform = UvTransform {
        offset: Vec2::splat(-0.5),
        rotation: 0.0,
        scale: Vec2::splat(2.0),
    };
    let info =
        r#", "extensions": {"KHR_texture_transform": {"offset": [-0.5, -0.5], "scale": [2, 2]}}"#;
    for (mode, wrap) in [
        (10497, repeat as fn(f32) -> f32),
        (33071, clamp),
        (33648, mirror),
    ] {
        let sampler = format!(r#"{{"wrapS": {mode}, "wrapT": {mode}}}"#);
        let checked = check(floor(Some(&sampler), info), transform, wrap);
        println!("wrap {mode}: {checked} pixels checked");
        assert!(checked > 100, "{mode}");
    }
}

#[test]
fn occlusion_darkens_the_denoisers_albedo_only() {
    let scene = |strength: Option<f32>| {
        let mut doc = Doc::new();
        let occlusion = strength.map_or(String::new(), |s| {
            let clamp = Some(r#"{"wrapS": 33071, "wrapT": 33071}"#);
            let t = doc.texture(2, 1, &[[255, 0, 0, 255], [0, 0, 0, 255]], clamp);
            format!(r#", "occlusionTexture": {{"index": {t}, "strength": {s}}}"#)
        });
        let m = doc.material(&format!(
            r#"{{"pbrMetallicRoughness": {{"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}}{occlusion}}}"#
        ));
        uv_plane(&mut doc, 1.0, 0.0, false, m, &[]);
        doc.light(
            r#"{"type": "point", "intensity": 10}"#,
            r#""translation": [0, 1, 0]"#,
        );
        VIEW.add_to(&mut doc);
        doc.load("occluded.gltf")
    };
    let left = VIEW.pixels_in([-1.0, -0.6], [-1.0, 1.0]);
    let right = VIEW.pixels_in([0.6, 1.0], [-1.0, 1.0]);
    let occluded = scene(Some(1.0));
    assert!(occluded.features().occlusion && occluded.warnings.is_empty());
    for (strength, want_right) in [(1.0, 0.0), (0.5, 0.25)] {
        let [albedo, _] = gbuffer_once(scene(Some(strength)), VIEW.size);
        let (l, r) = (mean_at(&albedo, &left, 0), mean_at(&albedo, &right, 0));
        println!("strength {strength}: albedo {l} unoccluded, {r} occluded");
        assert!(
            (l - 0.5).abs() < 0.02 && (r - want_right).abs() < 0.02,
            "{l} {r}"
        );
    }
    // Light transport ignores it: the same radiance with and without the texture.
    let with = render_once(occluded, Algorithm::PathTracing, 4, 3, VIEW.size);
    let without = render_once(scene(None), Algorithm::PathTracing, 4, 3, VIEW.size);
    assert_eq!(with.pixels, without.pixels);
}
