//! Bidirectional path tracing converges to the path tracer's image: equal channel means (within
//! their noise and 2%) and a per-pixel relative MSE between the two estimates that their own noise
//! explains (estimated from two independent seeds of each). On `caustics`, BDPT's channel means
//! are compared with a high-sample path-traced reference away from the pixels that see the glass
//! sphere: the caustic seen through the glass and the lamp seen in it are specular chains only the
//! camera's BSDF sampling finds, with heavy-tailed noise in both estimators. With three
//! connections a camera vertex instead of one, BDPT converges alike and its noise on the Cornell
//! box halves; with the balance heuristic instead of the power heuristic, or with a connection
//! roulette far stronger than the default's, it converges alike.

use glam::Vec2;
use lucid_engine::capture::ImageData;
use lucid_passes::light_transport::bdpt::MisHeuristic;
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::bdpt_stats::{relative_noise, Comparison};
use lucid_tests::render::{render_accumulated, scene};
use std::num::NonZeroU32;
use std::sync::OnceLock;
use std::time::Instant;

const SIZE: u32 = 32;
const SPP_PER_FRAME: SamplesPerPixel = SamplesPerPixel::new(4).unwrap();

fn render(name: &str, algorithm: Algorithm, frames: u32, seed: u32) -> ImageData {
    let settings = Settings {
        algorithm,
        seed,
        ..Settings::default()
    };
    render_with(name, settings, frames)
}

/// BDPT with `tuning`'s connections and MIS heuristic (the rest of it ignored).
fn render_bdpt(name: &str, tuning: Settings, frames: u32, seed: u32) -> ImageData {
    let settings = Settings {
        algorithm: Algorithm::Bidirectional,
        seed,
        ..tuning
    };
    render_with(name, settings, frames)
}

/// `frames` frames of `settings` at SPP_PER_FRAME samples each, accumulated.
fn render_with(name: &str, settings: Settings, frames: u32) -> ImageData {
    let start = Instant::now();
    let settings = Settings {
        samples_per_pixel: SPP_PER_FRAME,
        ..settings
    };
    let image = render_accumulated(scene(name), (SIZE, SIZE), settings, frames);
    let tuning = match settings.algorithm {
        Algorithm::Bidirectional => format!(
            " (connections: {}, {})",
            settings.bdpt_connections,
            settings.bdpt_mis.label()
        ),
        _ => String::new(),
    };
    eprintln!(
        "{name} {}{tuning} {} spp seed {}: {:.1} s",
        settings.algorithm.short_name(),
        frames * SPP_PER_FRAME.get(),
        settings.seed,
        start.elapsed().as_secs_f64()
    );
    image
}

/// Path tracing (seeds 1 and 2) and BDPT (seeds 3 and 4) renders of one scene.
struct Renders {
    pt: [ImageData; 2],
    bdpt: [ImageData; 2],
}

impl Renders {
    /// Renders `name` twice with each algorithm (independent seeds).
    fn new(name: &str, frames: u32) -> Self {
        Self {
            pt: [1, 2].map(|seed| render(name, Algorithm::PathTracing, frames, seed)),
            bdpt: [3, 4].map(|seed| render(name, Algorithm::Bidirectional, frames, seed)),
        }
    }

    /// BDPT compared with path tracing.
    fn compare(&self, name: &str) -> Comparison {
        let c = Comparison::new([&self.pt[0], &self.pt[1]], [&self.bdpt[0], &self.bdpt[1]]);
        c.report(name);
        c
    }
}

/// Frames of the Cornell box renders.
const CORNELL_FRAMES: u32 = 32;

/// The Cornell box's renders, made once for the tests that share them.
fn cornell_box() -> &'static Renders {
    static RENDERS: OnceLock<Renders> = OnceLock::new();
    RENDERS.get_or_init(|| Renders::new("cornell-box", CORNELL_FRAMES))
}

#[test]
fn cornell_box_matches_path_tracing() {
    let c = cornell_box().compare("cornell-box");
    c.assert_converged("cornell-box", 1.3);
}

/// BDPT renders of the Cornell box with `tuning`'s connections and MIS heuristic (seeds 3 and 4),
/// once checked to converge to the path tracer's image (`label` names them).
fn cornell_box_bdpt_converging(tuning: Settings, label: &str) -> [ImageData; 2] {
    let images = [3, 4].map(|seed| render_bdpt("cornell-box", tuning, CORNELL_FRAMES, seed));
    let pt = &cornell_box().pt;
    let c = Comparison::new([&pt[0], &pt[1]], [&images[0], &images[1]]);
    c.report(label);
    c.assert_converged(label, 1.3);
    images
}

/// With three connections a camera vertex BDPT still converges to the path tracer's image, with
/// less noise than with one at the same samples.
#[test]
fn cornell_box_with_three_connections_matches_path_tracing_with_less_noise() {
    let three = Settings {
        bdpt_connections: NonZeroU32::new(3).unwrap(),
        ..Settings::default()
    };
    let more = cornell_box_bdpt_converging(three, "cornell-box, 3 connections");
    let one = &cornell_box().bdpt;
    let (noise_one, noise_more) = (
        relative_noise([&one[0], &one[1]]),
        relative_noise([&more[0], &more[1]]),
    );
    eprintln!("relative noise: 1 connection {noise_one:.5}, 3 connections {noise_more:.5}");
    assert!(
        noise_more < 0.9 * noise_one,
        "{noise_more} against {noise_one}"
    );
}

/// With the balance heuristic BDPT converges to the path tracer's image too, and differs from the
/// power heuristic's image of the same seeds (the setting reaches the shaders).
#[test]
fn cornell_box_with_the_balance_heuristic_matches_path_tracing() {
    let balance = Settings {
        bdpt_mis: MisHeuristic::Balance,
        ..Settings::default()
    };
    let images = cornell_box_bdpt_converging(balance, "cornell-box, balance heuristic");
    let power = &cornell_box().bdpt;
    assert_ne!(
        images[0].pixels, power[0].pixels,
        "the same image as the power heuristic's"
    );
}

/// With connection roulette twenty times the default's threshold (a connection that would add less
/// than twice what its camera subpath has gathered is traced with probability in proportion, and
/// every light-tracing connection with probability its MIS weight) BDPT still converges to the
/// path tracer's image: the roulette weighs up what it keeps. With the
/// roulette off, the image of the same seed differs from the default's (the setting reaches the
/// shaders).
#[test]
fn cornell_box_with_strong_connection_roulette_matches_path_tracing() {
    let strong = Settings {
        bdpt_connection_roulette: 2.0,
        ..Settings::default()
    };
    cornell_box_bdpt_converging(strong, "cornell-box, connection roulette 2");
    let off = Settings {
        bdpt_connection_roulette: 0.0,
        ..Settings::default()
    };
    let image = render_bdpt("cornell-box", off, CORNELL_FRAMES, 3);
    assert_ne!(
        image.pixels,
        cornell_box().bdpt[0].pixels,
        "the same image as with the default roulette"
    );
}

#[test]
fn cornell_teapot_matches_path_tracing() {
    let c = Renders::new("cornell-teapot", 12).compare("cornell-teapot");
    c.assert_converged("cornell-teapot", 1.4);
}

/// Copies of `images` with the pixels that see a sphere of `scene` (footprint sampled 4 x 4,
/// radius grown by 5%) set to zero.
fn mask_spheres(name: &str, images: &[ImageData]) -> Vec<ImageData> {
    let scene = scene(name);
    let sees_sphere = |x: u32, y: u32| {
        (0..16).any(|k| {
            let uv = Vec2::new(
                (x as f32 + (k % 4) as f32 / 3.0) / SIZE as f32,
                (y as f32 + (k / 4) as f32 / 3.0) / SIZE as f32,
            );
            let ray = scene.camera.generate_ray(
                Vec2::new(2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y),
                1.0,
                Vec2::ZERO,
            );
            scene.spheres.iter().any(|s| {
                let oc = ray.origin - s.center;
                let b = oc.dot(ray.dir);
                let r = 1.05 * s.radius;
                b * b - oc.length_squared() + r * r >= 0.0 && b < 0.0
            })
        })
    };
    images
        .iter()
        .map(|image| {
            let mut out = image.clone();
            for y in 0..SIZE {
                for x in 0..SIZE {
                    if sees_sphere(x, y) {
                        out.pixels[(y * SIZE + x) as usize] = [0.0, 0.0, 0.0, 1.0];
                    }
                }
            }
            out
        })
        .collect()
}

#[test]
fn caustics_matches_a_path_traced_reference() {
    let reference = [1, 2].map(|seed| render("caustics", Algorithm::PathTracing, 512, seed));
    let bdpt = [3, 4].map(|seed| render("caustics", Algorithm::Bidirectional, 64, seed));
    let m = mask_spheres("caustics", &[reference, bdpt].concat());
    let c = Comparison::new([&m[0], &m[1]], [&m[2], &m[3]]);
    eprintln!(
        "caustics vs reference: {c:?}\n  mean difference {:.2}% ({:.1} sigma)",
        100.0 * c.mean_difference(),
        c.mean_z()
    );
    // Per pixel, the path tracer's noise here is too heavy-tailed for a pair of renders to
    // estimate (the caustic in the sphere's shadow is a rare hit of the lamp through the glass),
    // so only the means are compared.
    c.assert_converged("caustics", f64::INFINITY);
}
