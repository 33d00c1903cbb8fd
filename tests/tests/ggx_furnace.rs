//! The GGX materials against a CPU reference of their models: a sphere in the white furnace
//! (uniform sky of radiance 1) shows, at each pixel, the BSDF's directional albedo for the pixel's
//! view angle, `E(μ) = ∫ f(wo, wi) cos θi dwi` (the sphere is convex: every reflected path reaches
//! the sky in one bounce). For the rough conductor `f = F(wi·h) D(h) G2(wo, wi) / (4 μ cos θi)`;
//! for glTF's metallic-roughness model `f` mixes that metal (Fresnel F0 = base colour) with a
//! dielectric by the metallic factor, the dielectric being the same specular lobe with F0 = 0.04
//! plus Lambertian diffuse of the base colour weighted by `1 - F(wi·h)`. `E` is integrated here on
//! a grid of incident directions from the models' definitions (GGX distribution, height-correlated
//! Smith masking-shadowing, Schlick's Fresnel), independently of the shaders' sampling (visible
//! normals, the lobe choice) and multiple importance sampling; path tracing and bidirectional path
//! tracing must both match it, averaged over rings of equal view angle.

use glam::{Vec2, Vec3};
use lucid_engine::scene::{Camera, Environment, Material, Scene};
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::render::render_accumulated;

const SIZE: u32 = 64;
/// The base colour (the metal's F0, the diffuse albedo) per channel: coloured, so Fresnel's rise
/// at grazing angles shows.
const F0: [f64; 3] = [1.0, 0.6, 0.2];
/// The dielectric layer's F0 in glTF's model (IOR 1.5).
const DIELECTRIC_F0: f64 = 0.04;

/// A material of the furnace sphere: `metallic` 1 is the conductor [`Material::conductor`], less is
/// glTF's metallic-roughness model [`Material::metal_rough`]; the base colour is [`F0`].
#[derive(Clone, Copy, Debug)]
struct Model {
    metallic: f64,
    alpha: f64,
}
/// Relative tolerance on a ring's mean (about 200-500 pixels of 128 samples each).
const TOLERANCE: f64 = 0.015;

fn ggx_d(cos_h: f64, alpha: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let d = cos_h * cos_h * (a2 - 1.0) + 1.0;
    a2 / (std::f64::consts::PI * d * d)
}

fn smith_lambda(cos: f64, alpha: f64) -> f64 {
    let c2 = cos * cos;
    let t2 = (1.0 - c2).max(0.0) / c2.max(1e-12);
    0.5 * ((1.0 + alpha * alpha * t2).sqrt() - 1.0)
}

/// Directional albedo per channel of `model` at view cosine `mu`: midpoint rule over the incident
/// hemisphere, `n` steps in each angle.
fn directional_albedo(mu: f64, model: Model, n: usize) -> [f64; 3] {
    let Model { metallic, alpha } = model;
    let wo = [(1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu];
    let (dt, dp) = (
        std::f64::consts::FRAC_PI_2 / n as f64,
        2.0 * std::f64::consts::PI / n as f64,
    );
    let lambda_o = smith_lambda(mu, alpha);
    let mut sum = [0.0; 3];
    for i in 0..n {
        let theta = (i as f64 + 0.5) * dt;
        let (sin_t, cos_t) = theta.sin_cos();
        let lambda_i = smith_lambda(cos_t, alpha);
        for j in 0..n {
            let phi = (j as f64 + 0.5) * dp;
            let wi = [sin_t * phi.cos(), sin_t * phi.sin(), cos_t];
            let h = [wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]];
            let len = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
            let cos_h = h[2] / len;
            let wi_h = (wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]) / len;
            let g2 = 1.0 / (1.0 + lambda_o + lambda_i);
            // f · cos_i dω: the specular lobe F D G2 / (4 μ cos_i) with F mixed between the metal's
            // and the dielectric's, and the dielectric's diffuse (1 - F) c / π.
            let d_omega = sin_t * dt * dp;
            let specular = ggx_d(cos_h, alpha) * g2 / (4.0 * mu) * d_omega;
            let m5 = (1.0 - wi_h).clamp(0.0, 1.0).powi(5);
            let dielectric_f = DIELECTRIC_F0 + (1.0 - DIELECTRIC_F0) * m5;
            let diffuse =
                (1.0 - metallic) * (1.0 - dielectric_f) / std::f64::consts::PI * cos_t * d_omega;
            for (c, s) in sum.iter_mut().enumerate() {
                let metal_f = F0[c] + (1.0 - F0[c]) * m5;
                let f = metallic * metal_f + (1.0 - metallic) * dielectric_f;
                *s += f * specular + diffuse * F0[c];
            }
        }
    }
    sum
}

/// The furnace with a sphere of `model`.
fn furnace(model: Model) -> Scene {
    let mut scene = Scene::new("ggx-furnace");
    let color = Vec3::new(F0[0] as f32, F0[1] as f32, F0[2] as f32);
    let alpha = model.alpha as f32;
    let material = if model.metallic >= 1.0 {
        Material::conductor("metal", color, alpha)
    } else {
        Material::metal_rough("metal-rough", color, model.metallic as f32, alpha)
    };
    let material = scene.add_material(material);
    scene.add_sphere(Vec3::ZERO, 1.0, material);
    scene.environment = Environment::Constant(Vec3::ONE);
    scene.camera = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 40.0);
    scene.validate().expect("valid scene");
    scene
}

/// The view cosines (`dot(n, -d)`) of a 4x4 lattice of rays over pixel (x, y), or None where one
/// of them misses the unit sphere at the origin.
fn pixel_cosines(camera: &Camera, x: u32, y: u32) -> Option<Vec<f64>> {
    let mut out = Vec::with_capacity(16);
    for sy in 0..4 {
        for sx in 0..4 {
            let film = Vec2::new(
                (x as f32 + (sx as f32 + 0.5) / 4.0) / SIZE as f32,
                (y as f32 + (sy as f32 + 0.5) / 4.0) / SIZE as f32,
            );
            let ndc = Vec2::new(2.0 * film.x - 1.0, 1.0 - 2.0 * film.y);
            let ray = camera.generate_ray(ndc, 1.0, Vec2::ZERO);
            let (o, d) = (ray.origin, ray.dir);
            let b = o.dot(d);
            let disc = b * b - (o.dot(o) - 1.0);
            if disc <= 0.0 {
                return None;
            }
            let n = (o + d * (-b - disc.sqrt())).normalize();
            out.push(f64::from(n.dot(-d)));
        }
    }
    Some(out)
}

fn check(model: Model, algorithm: Algorithm) {
    // E(μ) tabulated at 65 cosines, linearly interpolated.
    let table: Vec<[f64; 3]> = (0..=64)
        .map(|i| directional_albedo((f64::from(i) / 64.0).max(1e-3), model, 400))
        .collect();
    let albedo = |mu: f64| {
        let s = mu.clamp(0.0, 1.0) * 64.0;
        let i = (s.floor() as usize).min(63);
        let f = s - i as f64;
        [0, 1, 2].map(|c| table[i][c] * (1.0 - f) + table[i + 1][c] * f)
    };
    let scene = furnace(model);
    let camera = scene.camera;
    let settings = Settings {
        algorithm,
        samples_per_pixel: SamplesPerPixel::new(8).unwrap(),
        ..Settings::default()
    };
    let image = render_accumulated(scene, (SIZE, SIZE), settings, 16);
    // Rings of view cosine: sums of rendered and expected values per channel, and pixel counts.
    const RINGS: [f64; 5] = [0.4, 0.55, 0.7, 0.85, 0.95];
    let mut rings = vec![([0.0f64; 3], [0.0f64; 3], 0u32); RINGS.len()];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let Some(cosines) = pixel_cosines(&camera, x, y) else {
                continue;
            };
            let lowest = cosines.iter().copied().fold(1.0, f64::min);
            let Some(ring) = RINGS.iter().rposition(|&r| lowest >= r) else {
                continue;
            };
            let expected = cosines.iter().fold([0.0; 3], |acc, &mu| {
                let e = albedo(mu);
                [0, 1, 2].map(|c| acc[c] + e[c] / cosines.len() as f64)
            });
            let got = image.get(x, y).expect("pixel");
            let entry = &mut rings[ring];
            for c in 0..3 {
                entry.0[c] += f64::from(got[c]);
                entry.1[c] += expected[c];
            }
            entry.2 += 1;
        }
    }
    for (ring, (got, want, count)) in rings.iter().enumerate() {
        assert!(*count >= 20, "ring {ring}: only {count} pixels");
        for c in 0..3 {
            let rel = (got[c] - want[c]).abs() / want[c];
            eprintln!(
                "{algorithm:?} {model:?} ring mu >= {}: channel {c} rendered {:.4} expected {:.4} ({count} px)",
                RINGS[ring],
                got[c] / f64::from(*count),
                want[c] / f64::from(*count)
            );
            assert!(
                rel < TOLERANCE,
                "{algorithm:?}, {model:?}, view cosine >= {}: channel {c} renders {:.4}, the CPU reference gives {:.4}",
                RINGS[ring],
                got[c] / f64::from(*count),
                want[c] / f64::from(*count)
            );
        }
    }
}

#[test]
fn the_reference_integration_conserves_energy_and_loses_it_with_roughness() {
    // A white conductor reflects at most all light; GGX without multiple scattering loses more
    // the rougher it is (this integration: 0.3% at alpha 0.05, 12% at 0.3, 57% at 0.8 at normal
    // incidence; a visible-normal Monte Carlo estimate of the same model, 400 000 samples, agrees
    // within 1.5e-3).
    let white = |mu: f64, alpha: f64| directional_albedo(mu, metal(alpha), 800)[0];
    for mu in [0.3, 0.6, 1.0] {
        let losses: Vec<f64> = [0.05, 0.3, 0.8].iter().map(|&a| white(mu, a)).collect();
        assert!(
            losses[0] <= 1.0 + 1e-3 && losses[0] > 0.97,
            "mu {mu}: {losses:?}"
        );
        assert!(
            losses[1] < losses[0] && losses[2] < losses[1] - 0.1,
            "mu {mu}: {losses:?}"
        );
    }
}

#[test]
fn the_metal_rough_reference_is_the_conductor_at_full_metal_and_white_diffuse_keeps_energy() {
    // At metallic 1 the model is the conductor. At 0 with a white base colour the diffuse layer
    // takes what the specular layer leaves (1 - F at the half vector, as glTF defines it), which
    // keeps the sum near 1 without bounding it: at alpha 0.4 the specification's model reflects
    // 0.9% less than it receives at normal view and 1.6% more at a view cosine of 0.3.
    for mu in [0.3, 0.7, 1.0] {
        let full = directional_albedo(
            mu,
            Model {
                metallic: 1.0,
                alpha: 0.4,
            },
            400,
        );
        assert_eq!(full, directional_albedo(mu, metal(0.4), 400));
        let plastic = directional_albedo(
            mu,
            Model {
                metallic: 0.0,
                alpha: 0.4,
            },
            400,
        )[0];
        assert!((plastic - 1.0).abs() < 0.02, "mu {mu}: {plastic}");
    }
}

fn metal(alpha: f64) -> Model {
    Model {
        metallic: 1.0,
        alpha,
    }
}

#[test]
fn path_tracing_matches_the_cpu_reference() {
    check(metal(0.3), Algorithm::PathTracing);
    check(metal(0.8), Algorithm::PathTracing);
}

#[test]
fn bidirectional_path_tracing_matches_the_cpu_reference() {
    check(metal(0.5), Algorithm::Bidirectional);
}

#[test]
fn path_tracing_matches_the_cpu_reference_for_gltf_metal_rough() {
    check(
        Model {
            metallic: 0.0,
            alpha: 0.3,
        },
        Algorithm::PathTracing,
    );
    check(
        Model {
            metallic: 0.5,
            alpha: 0.6,
        },
        Algorithm::PathTracing,
    );
}

#[test]
fn bidirectional_path_tracing_matches_the_cpu_reference_for_gltf_metal_rough() {
    check(
        Model {
            metallic: 0.25,
            alpha: 0.4,
        },
        Algorithm::Bidirectional,
    );
}
