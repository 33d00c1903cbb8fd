//! Texture filtering: every texture carries a mip chain, and the first hit of a camera ray looks
//! its textures up at the level its ray cone covers (Akenine-Möller et al. 2019). A checkerboard
//! of one-texel squares seen from afar (several texels per pixel) shows its mean, grey, in every
//! pixel instead of aliasing to black and white; a coarse one seen as close keeps its contrast.

use lucid_engine::capture::ImageData;
use lucid_engine::scene::Scene;
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::gltf::{uv_plane, Doc, TopView};
use lucid_tests::render::{gbuffer_once, render_accumulated};

const VIEW: TopView = TopView {
    height: 2.0,
    yfov: 1.0,
    size: 32,
};
/// Half the floor's side: it fills the view (whose half-extent is 2 tan 0.5 = 1.09).
const HALF: f32 = 2.0;

/// A floor whose base colour is an `n` x `n` checkerboard of black and white texels (sRGB), lit
/// by a point light.
fn checker_floor(n: u32) -> Scene {
    let mut doc = Doc::new();
    let texels: Vec<[u8; 4]> = (0..n * n)
        .map(|i| {
            if (i % n + i / n) % 2 == 0 {
                [0, 0, 0, 255]
            } else {
                [255; 4]
            }
        })
        .collect();
    let t = doc.texture(n, n, &texels, None);
    doc.uses("KHR_materials_specular");
    let m = doc.material(&format!(
        r#"{{"pbrMetallicRoughness": {{"metallicFactor": 0, "baseColorTexture": {{"index": {t}}}}},
            "extensions": {{"KHR_materials_specular": {{"specularFactor": 0}}}}}}"#
    ));
    uv_plane(&mut doc, HALF, 0.0, false, m, &[]);
    doc.light(
        r#"{"type": "point", "intensity": 10}"#,
        r#""translation": [0, 1, 0]"#,
    );
    VIEW.add_to(&mut doc);
    doc.load("checker.gltf")
}

fn red(image: &ImageData) -> Vec<f32> {
    image.pixels.iter().map(|p| p[0]).collect()
}

fn mean_and_deviation(values: &[f32]) -> (f32, f32) {
    let mean = values.iter().sum::<f32>() / values.len() as f32;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f32>() / values.len() as f32;
    (mean, var.sqrt())
}

#[test]
fn a_minified_checkerboard_shows_its_mean_in_every_pixel() {
    // 512 texels over 4 m, a pixel covering 0.068 m: about 9 texels across per pixel.
    let [albedo, _] = gbuffer_once(checker_floor(512), VIEW.size);
    let (mean, deviation) = mean_and_deviation(&red(&albedo));
    println!("minified: albedo {mean:.3} +- {deviation:.3}");
    assert!((mean - 0.5).abs() < 0.03, "{mean}");
    assert!(deviation < 0.03, "pixels alias: deviation {deviation}");
    // Path tracing's first hit filters the same way: at one sample per pixel the floor under a
    // point light varies smoothly, not by texel.
    let settings = Settings {
        algorithm: Algorithm::PathTracing,
        samples_per_pixel: SamplesPerPixel::new(1).unwrap(),
        max_depth: 2,
        ..Settings::default()
    };
    let traced = render_accumulated(checker_floor(512), (VIEW.size, VIEW.size), settings, 1);
    let centre: Vec<f32> = (12..20)
        .flat_map(|y| (12..20).map(move |x| (x, y)))
        .map(|(x, y)| traced.get(x, y).unwrap()[0])
        .collect();
    let (mean, deviation) = mean_and_deviation(&centre);
    println!("traced centre: {mean:.4} +- {deviation:.4}");
    assert!(deviation < 0.1 * mean, "deviation {deviation} of {mean}");
}

#[test]
fn a_magnified_checkerboard_stays_sharp() {
    // 8 texels over 4 m: a texel spans about 7 pixels, so level 0 is read, bilinearly: values
    // ramp between texel centres, 0.5 + 0.5ab for a, b uniform in [-1, 1], a deviation of 1/6
    // over the pixels. Level 1 or above of this checkerboard is uniformly grey (deviation 0).
    let [albedo, _] = gbuffer_once(checker_floor(8), VIEW.size);
    let (mean, deviation) = mean_and_deviation(&red(&albedo));
    println!("magnified: albedo {mean:.3} +- {deviation:.3}");
    assert!(
        deviation > 0.12,
        "the checkerboard is blurred: deviation {deviation}"
    );
}
