//! Lucid's path tracer and bidirectional path tracer against Mitsuba 3 on Mitsuba's own Cornell box
//! (`cornell-box`): the reference EXR in `tests/references/` was rendered by
//! `make_cornell_reference.py` (scalar_rgb, box filter, path integrator, max_depth 8, 256x256). Mean
//! per channel within 1%, and relative MSE no larger than the noise expected at the sample count.

use lucid_engine::capture::{self, ImageData};
use lucid_engine::metrics;
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::render::{render_accumulated, scene};
use std::path::PathBuf;

const RELMSE_EPS: f64 = 1e-2;

fn reference() -> (ImageData, serde_json::Value) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("references");
    let image = capture::load(dir.join("cornell_box_mitsuba_256.exr")).expect("reference EXR");
    let meta: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("cornell_box_mitsuba_256.json")).expect("reference JSON"),
    )
    .expect("reference JSON parses");
    (image, meta)
}

fn render(algorithm: Algorithm, max_depth: u32, seed: u32, (spp, frames): (u32, u32)) -> ImageData {
    let settings = Settings {
        algorithm,
        samples_per_pixel: SamplesPerPixel::new(spp).expect("at least one sample per pixel"),
        max_depth,
        seed,
        ..Settings::default()
    };
    render_accumulated(scene("cornell-box"), (256, 256), settings, frames)
}

fn average(a: &ImageData, b: &ImageData) -> ImageData {
    let pixels = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| {
            [
                0.5 * (p[0] + q[0]),
                0.5 * (p[1] + q[1]),
                0.5 * (p[2] + q[2]),
                1.0,
            ]
        })
        .collect();
    ImageData::from_pixels(a.width, a.height, pixels).unwrap()
}

/// The relative MSE two independent estimates of the reference's noise level predict for their mean:
/// per pixel, Var(mean) = (a - b)^2 / 4, plus the reference's own variance.
fn expected_rel_mse(a: &ImageData, b: &ImageData, reference: &ImageData, ref_var: [f64; 3]) -> f64 {
    let mut sum = 0.0;
    for ((p, q), r) in a.pixels.iter().zip(&b.pixels).zip(&reference.pixels) {
        for c in 0..3 {
            let d = (p[c] - q[c]) as f64;
            let r = r[c] as f64;
            sum += (d * d / 4.0 + ref_var[c]) / (r * r + RELMSE_EPS);
        }
    }
    sum / (3 * a.pixels.len()) as f64
}

fn mean_error(image: &ImageData, reference_mean: [f64; 3]) -> [f64; 3] {
    let m = image.mean_rgb();
    [0, 1, 2].map(|c| (m[c] - reference_mean[c]) / reference_mean[c])
}

#[test]
fn path_tracing_matches_mitsuba() {
    matches_mitsuba(Algorithm::PathTracing);
}

#[test]
fn bidirectional_path_tracing_matches_mitsuba() {
    matches_mitsuba(Algorithm::Bidirectional);
}

fn matches_mitsuba(algorithm: Algorithm) {
    let (reference, meta) = reference();
    assert_eq!((reference.width, reference.height), (256, 256));
    assert_eq!(meta["max_depth"], 8);
    let ref_var = [0, 1, 2].map(|c| meta["ref_pixel_var_mean"][c].as_f64().unwrap());
    let ref_mean = reference.mean_rgb();

    // Two independent renders (different seeds) of 32 spp each.
    let a = render(algorithm, 8, 1, (8, 4));
    let b = render(algorithm, 8, 2, (8, 4));
    let lucid = average(&a, &b);
    let err = mean_error(&lucid, ref_mean);
    for c in 0..3 {
        assert!(
            err[c].abs() < 0.01,
            "{algorithm:?}, channel {c}: mean differs by {:.3}% ({err:?})",
            100.0 * err[c]
        );
    }
    let rel_mse = metrics::rel_mse(&lucid, &reference, RELMSE_EPS).unwrap();
    let expected = expected_rel_mse(&a, &b, &reference, ref_var);
    eprintln!(
        "{algorithm:?}: mean error {err:?}, relMSE {rel_mse:.5}, expected from noise {expected:.5}"
    );
    assert!(
        rel_mse <= 1.2 * expected,
        "{algorithm:?}: relMSE {rel_mse:.5} exceeds the noise expected at 64 spp ({expected:.5}): a bias, not noise"
    );
}

#[test]
fn the_comparison_detects_a_wrong_path_depth() {
    // Cutting paths at depth 4 removes ~5% of the light: the same criteria must reject it.
    let (reference, _) = reference();
    let short = render(Algorithm::PathTracing, 4, 3, (8, 2));
    let err = mean_error(&short, reference.mean_rgb());
    assert!(
        err.iter().any(|e| e.abs() > 0.01),
        "depth 4 must differ by more than 1%: {err:?}"
    );
}
