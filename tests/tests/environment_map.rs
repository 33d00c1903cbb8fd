//! Environment maps (`--env`): an equirectangular map lights the scene, its radiance looked up
//! bilinearly and next-event estimation drawing directions from its luminance (combined with BSDF
//! sampling by MIS). A constant map is the white furnace; a map that is dark but for one bright
//! texel lights a diffuse floor as the CPU integrates the map, with little noise (BSDF sampling
//! alone would hit that texel about once in 3000 samples).

use glam::{Vec2, Vec3};
use lucid_engine::capture::ImageData;
use lucid_engine::scene::environment_map::uv_to_direction;
use lucid_engine::scene::{Camera, Material, Scene, TexelData, Texture};
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::render::render_accumulated;

const SIZE: u32 = 32;
const MAP_WIDTH: u32 = 128;
const MAP_HEIGHT: u32 = 64;
/// The bright texel (column, row) and its radiance; every other texel has `BACKGROUND`.
const SUN_TEXEL: (u32, u32) = (80, 20);
const SUN: f32 = 2000.0;
const BACKGROUND: f32 = 0.02;
const ALBEDO: f32 = 0.5;

fn map(texel: impl Fn(u32, u32) -> f32) -> Texture {
    let texels = (0..MAP_HEIGHT)
        .flat_map(|y| (0..MAP_WIDTH).map(move |x| (x, y)))
        .map(|(x, y)| {
            let v = texel(x, y);
            [v, v, v, 1.0]
        })
        .collect();
    Texture {
        name: "map".into(),
        width: MAP_WIDTH,
        height: MAP_HEIGHT,
        srgb: false,
        texels: TexelData::RgbaF32(texels),
    }
}

fn sun_map(x: u32, y: u32) -> f32 {
    if (x, y) == SUN_TEXEL {
        SUN
    } else {
        BACKGROUND
    }
}

/// The map's radiance at `uv` as the shaders look it up: bilinear, repeating around, clamped at
/// the poles.
fn bilinear(uv: Vec2) -> f32 {
    let st = uv * Vec2::new(MAP_WIDTH as f32, MAP_HEIGHT as f32) - 0.5;
    let (i, f) = (st.floor(), st - st.floor());
    let fetch = |x: i32, y: i32| {
        let x = x.rem_euclid(MAP_WIDTH as i32) as u32;
        let y = y.clamp(0, MAP_HEIGHT as i32 - 1) as u32;
        sun_map(x, y)
    };
    let (x, y) = (i.x as i32, i.y as i32);
    let a = fetch(x, y) * (1.0 - f.x) + fetch(x + 1, y) * f.x;
    let b = fetch(x, y + 1) * (1.0 - f.x) + fetch(x + 1, y + 1) * f.x;
    a * (1.0 - f.y) + b * f.y
}

/// Irradiance on an upward-facing surface under the sun map: `∫ L cos θ dω` over the upper
/// hemisphere, by the midpoint rule in image coordinates (dω = 2π² sin θ du dv).
fn irradiance() -> f64 {
    let (nu, nv) = (4096, 1024);
    let mut sum = 0.0f64;
    for j in 0..nv {
        let v = (j as f32 + 0.5) / nv as f32 * 0.5;
        let d = uv_to_direction(Vec2::new(0.0, v));
        let (cos_t, sin_t) = (d.y, (1.0 - d.y * d.y).max(0.0).sqrt());
        for i in 0..nu {
            let u = (i as f32 + 0.5) / nu as f32;
            sum += f64::from(bilinear(Vec2::new(u, v)) * cos_t * sin_t);
        }
    }
    let (du, dv) = (1.0 / nu as f64, 0.5 / nv as f64);
    sum * 2.0 * std::f64::consts::PI.powi(2) * du * dv
}

/// A diffuse floor (the top of a sphere of radius 1000, flat over the view) seen from above.
fn floor_under(map: Texture) -> Scene {
    let mut scene = Scene::new("floor-under-a-map");
    let floor = scene.add_material(Material::diffuse("floor", Vec3::splat(ALBEDO)));
    scene.add_sphere(Vec3::new(0.0, -1000.0, 0.0), 1000.0, floor);
    scene.set_environment_map(map);
    scene.camera = Camera::look_at(Vec3::new(0.0, 3.0, 0.0), Vec3::ZERO, Vec3::Z, 30.0);
    scene.validate().expect("valid scene");
    scene
}

fn render(scene: Scene, algorithm: Algorithm, spp: u32, frames: u32) -> ImageData {
    let settings = Settings {
        algorithm,
        samples_per_pixel: SamplesPerPixel::new(spp).unwrap(),
        ..Settings::default()
    };
    render_accumulated(scene, (SIZE, SIZE), settings, frames)
}

/// Mean and relative standard deviation over the pixels of channel 0.
fn mean_and_spread(image: &ImageData) -> (f64, f64) {
    let values: Vec<f64> = image.pixels.iter().map(|p| f64::from(p[0])).collect();
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / values.len() as f64;
    (mean, var.sqrt() / mean)
}

#[test]
fn the_cpu_reference_sees_the_bright_texel() {
    // The bright texel's share dwarfs the background's (0.02 π ≈ 0.063).
    let e = irradiance();
    let background = f64::from(BACKGROUND) * std::f64::consts::PI;
    assert!(e > 10.0 * background, "{e}");
    let direction = uv_to_direction(Vec2::new(
        (SUN_TEXEL.0 as f32 + 0.5) / MAP_WIDTH as f32,
        (SUN_TEXEL.1 as f32 + 0.5) / MAP_HEIGHT as f32,
    ));
    assert!(
        direction.y > 0.3,
        "the texel is well above the horizon: {direction}"
    );
}

fn check_floor(algorithm: Algorithm) {
    let expected = f64::from(ALBEDO) / std::f64::consts::PI * irradiance();
    let image = render(floor_under(map(sun_map)), algorithm, 16, 8);
    let (mean, spread) = mean_and_spread(&image);
    eprintln!("{algorithm:?}: floor {mean:.4} (CPU {expected:.4}), pixel spread {spread:.3}");
    assert!(
        (mean - expected).abs() < 0.02 * expected,
        "{algorithm:?}: the floor renders {mean:.4}, the map's integral gives {expected:.4}"
    );
    assert!(
        spread < 0.15,
        "{algorithm:?}: pixels spread by {spread:.3} of their mean at 128 samples"
    );
}

#[test]
fn path_tracing_lights_a_floor_as_the_map_integrates() {
    check_floor(Algorithm::PathTracing);
}

#[test]
fn bidirectional_path_tracing_lights_a_floor_as_the_map_integrates() {
    check_floor(Algorithm::Bidirectional);
}

#[test]
fn a_constant_map_is_the_white_furnace() {
    // A diffuse sphere of albedo 0.8 in a map of radiance 0.5 everywhere: 0.4 on the sphere, 0.5
    // around it.
    let mut scene = Scene::new("map-furnace");
    let grey = scene.add_material(Material::diffuse("grey", Vec3::splat(0.8)));
    scene.add_sphere(Vec3::ZERO, 1.0, grey);
    scene.set_environment_map(map(|_, _| 0.5));
    scene.camera = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 40.0);
    scene.validate().expect("valid scene");
    for algorithm in [Algorithm::PathTracing, Algorithm::Bidirectional] {
        let image = render(scene.clone(), algorithm, 8, 4);
        let centre = (SIZE / 2 - 4..SIZE / 2 + 4)
            .flat_map(|y| (SIZE / 2 - 4..SIZE / 2 + 4).map(move |x| (x, y)))
            .map(|(x, y)| image.get(x, y).unwrap()[1])
            .sum::<f32>()
            / 64.0;
        let corner = image.get(0, 0).unwrap()[1];
        eprintln!("{algorithm:?}: sphere {centre}, background {corner}");
        assert!(
            (centre - 0.4).abs() < 0.008,
            "{algorithm:?}: sphere {centre}"
        );
        assert!(
            (corner - 0.5).abs() < 1e-3,
            "{algorithm:?}: background {corner}"
        );
    }
}
