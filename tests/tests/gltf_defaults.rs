//! What a glTF file gets when it lacks a camera or a light: a camera framing the scene's bounds
//! from a three-quarter view, and a neutral sky, each with a note. Rendered at 64x64 on lavapipe.

use lucid_engine::capture::ImageData;
use lucid_engine::scene::{Environment, Scene};
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::gltf::{cube, plane, Doc};
use lucid_tests::render::render_accumulated;

const SIZE: u32 = 64;

fn render(scene: Scene, algorithm: Algorithm, spp: u32) -> ImageData {
    render_accumulated(
        scene,
        (SIZE, SIZE),
        Settings {
            algorithm,
            samples_per_pixel: SamplesPerPixel::new(spp).unwrap(),
            max_depth: 4,
            ..Settings::default()
        },
        1,
    )
}

/// The share of pixels brighter than `threshold` in some channel.
fn lit_share(image: &ImageData, threshold: f32) -> f32 {
    let lit = image
        .pixels
        .iter()
        .filter(|p| p[..3].iter().any(|&c| c > threshold))
        .count();
    lit as f32 / image.pixels.len() as f32
}

fn has_note(scene: &Scene, words: &[&str]) -> bool {
    scene
        .notes
        .iter()
        .any(|n| words.iter().all(|w| n.contains(w)))
}

#[test]
fn a_floor_without_a_camera_is_framed_from_above() {
    // A 2 m floor at y = 0 lit by a point light above it, and no camera: the old automatic camera
    // on +Z looking down -Z saw it edge-on (no lit pixel).
    let mut doc = Doc::new();
    let (positions, indices) = plane(1.0);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let m = doc.material(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0}}"#,
    );
    let mesh = doc.mesh(&[("POSITION", p)], Some(i), Some(m));
    doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
    doc.light(
        r#"{"type": "point", "intensity": 2000}"#,
        r#""translation": [0, 1, 0]"#,
    );
    let scene = doc.load("floor.gltf");
    assert!(
        has_note(&scene, &["no camera in floor.gltf", "three-quarter"]),
        "{:?}",
        scene.notes
    );
    assert!(
        !has_note(&scene, &["sky"]),
        "the light is enough: {:?}",
        scene.notes
    );
    let image = render(scene, Algorithm::PathTracing, 4);
    let share = lit_share(&image, 1e-3);
    println!("floor: {:.1}% of pixels lit", 100.0 * share);
    // The whole 2 m square in view from 30° above at 45° to the side fills about 29% of a square
    // image (a diamond in the frame); edge-on it filled none.
    assert!(share > 0.25, "{:.1}% of pixels lit", 100.0 * share);
    // The whole floor is in the frame: the border rows and columns see only the black background.
    let border_lit = (0..SIZE)
        .flat_map(|k| [(k, 0), (k, SIZE - 1), (0, k), (SIZE - 1, k)])
        .filter(|&(x, y)| image.get(x, y).unwrap()[..3].iter().any(|&c| c > 1e-3))
        .count();
    assert_eq!(border_lit, 0, "the floor reaches the image border");
}

#[test]
fn a_scene_without_light_renders_under_the_neutral_sky_with_both_algorithms() {
    let mut doc = Doc::new();
    let (positions, indices) = cube(0.5);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let m = doc.material(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1], "metallicFactor": 0}}"#,
    );
    let mesh = doc.mesh(&[("POSITION", p)], Some(i), Some(m));
    doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
    let scene = doc.load("dark.gltf");
    assert_eq!(scene.environment, Environment::NEUTRAL_SKY);
    assert!(
        has_note(&scene, &["no light in dark.gltf", "sky"]),
        "{:?}",
        scene.notes
    );
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    for algorithm in Algorithm::ALL {
        let image = render(scene.clone(), algorithm, 8);
        // Every pixel sees the sky or the cube lit by it (the darkest, the bottom face, is not
        // in view from above).
        let share = lit_share(&image, 0.05);
        let centre = image.get(SIZE / 2, SIZE / 2).unwrap();
        println!(
            "{}: {:.1}% lit, centre {centre:?}",
            algorithm.short_name(),
            100.0 * share
        );
        assert_eq!(share, 1.0, "{}: every pixel is lit", algorithm.short_name());
        // The cube's top face (albedo 0.6) under a sky of radiance about 0.9 above and 0.3
        // below: well lit, and darker than the sky behind it.
        assert!(
            centre[1] > 0.2 && centre[1] < 0.9,
            "{}: cube {centre:?}",
            algorithm.short_name()
        );
    }
}
