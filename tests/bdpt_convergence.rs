//! Bidirectional path tracing converges to the path tracer's image: equal channel means (within
//! their noise and 2%) and a per-pixel relative MSE between the two estimates that their own noise
//! explains (estimated from two independent seeds of each). On `caustics`, BDPT is compared with a
//! high-sample path-traced reference and must be closer to it than path tracing at equal samples.
//!
//! Renders stay at 4 samples per pixel per frame and accumulate frames: llvmpipe (lavapipe) ends
//! every loop of an invocation once their iterations add up to 65535, which silently drops
//! samples of long per-pixel sample loops.

#[path = "bdpt_stats.rs"]
mod bdpt_stats;

use bdpt_stats::{average, rel_mse, Comparison};
use lucid_engine::capture::ImageData;
use lucid_passes::renderer::{Algorithm, Settings};
use lucid_tests::render::{render_accumulated, scene};
use std::time::Instant;

const SIZE: u32 = 32;
const SPP_PER_FRAME: u32 = 4;

fn render(name: &str, algorithm: Algorithm, frames: u32, seed: u32) -> ImageData {
    let start = Instant::now();
    let settings = Settings {
        algorithm,
        samples_per_pixel: SPP_PER_FRAME,
        seed,
        ..Settings::default()
    };
    let image = render_accumulated(scene(name), (SIZE, SIZE), settings, frames);
    eprintln!(
        "{name} {} {} spp seed {seed}: {:.1} s",
        algorithm.short_name(),
        frames * SPP_PER_FRAME,
        start.elapsed().as_secs_f64()
    );
    image
}

/// Renders `name` twice with each algorithm (independent seeds) and compares them.
fn compare_with_path_tracing(name: &str, frames: u32) -> Comparison {
    let pt = [1, 2].map(|seed| render(name, Algorithm::PathTracing, frames, seed));
    let bdpt = [3, 4].map(|seed| render(name, Algorithm::Bidirectional, frames, seed));
    let c = Comparison::new([&pt[0], &pt[1]], [&bdpt[0], &bdpt[1]]);
    eprintln!(
        "{name}: {c:?}\n  mean difference {:.2}% ({:.1} sigma), relMSE ratio {:.3}",
        100.0 * c.mean_difference(),
        c.mean_z(),
        c.ratio()
    );
    c
}

fn assert_converged(name: &str, c: &Comparison, max_ratio: f64) {
    assert!(
        c.mean_difference() < 0.02 && c.mean_z() < 4.0,
        "{name}: channel means differ: {:?} vs {:?}",
        c.mean_a,
        c.mean_b
    );
    assert!(
        c.ratio() < max_ratio,
        "{name}: relative MSE {:.4} between the estimates, noise explains {:.4}",
        c.rel_mse,
        c.expected_rel_mse
    );
}

#[test]
fn cornell_box_matches_path_tracing() {
    let c = compare_with_path_tracing("cornell-box", 32);
    assert_converged("cornell-box", &c, 1.3);
}

#[test]
fn cornell_teapot_matches_path_tracing() {
    let c = compare_with_path_tracing("cornell-teapot", 12);
    assert_converged("cornell-teapot", &c, 1.4);
}

#[test]
fn caustics_matches_a_reference_and_beats_path_tracing() {
    let reference = [5, 6].map(|seed| render("caustics", Algorithm::PathTracing, 256, seed));
    let bdpt = [7, 8].map(|seed| render("caustics", Algorithm::Bidirectional, 16, seed));
    let c = Comparison::new([&reference[0], &reference[1]], [&bdpt[0], &bdpt[1]]);
    eprintln!(
        "caustics vs reference: {c:?}\n  mean difference {:.2}% ({:.1} sigma), relMSE ratio {:.3}",
        100.0 * c.mean_difference(),
        c.mean_z(),
        c.ratio()
    );
    assert_converged("caustics", &c, 1.5);

    let reference = average(&reference[0], &reference[1]);
    let pt = render("caustics", Algorithm::PathTracing, 16, 9);
    let (pt_error, bdpt_error) = (rel_mse(&pt, &reference), rel_mse(&bdpt[0], &reference));
    eprintln!("caustics relMSE at 64 spp: pt {pt_error:.4}, bdpt {bdpt_error:.4}");
    assert!(
        bdpt_error < 0.5 * pt_error,
        "BDPT should find the caustic with less noise: relMSE {bdpt_error:.4} vs {pt_error:.4}"
    );
}

#[test]
fn zz_dump() {
    let f = |a: Algorithm, fr, seed, tag: &str| {
        let img = render("caustics", a, fr, seed);
        let bytes: Vec<u8> = img
            .pixels
            .iter()
            .flat_map(|p| p.iter().flat_map(|v| v.to_le_bytes()))
            .collect();
        std::fs::write(format!("/tmp/c_{tag}.raw"), bytes).unwrap();
    };
    f(Algorithm::PathTracing, 256, 5, "r1");
    f(Algorithm::PathTracing, 256, 6, "r2");
    f(Algorithm::Bidirectional, 16, 7, "b1");
    f(Algorithm::Bidirectional, 16, 8, "b2");
    f(Algorithm::PathTracing, 16, 9, "p1");
}
