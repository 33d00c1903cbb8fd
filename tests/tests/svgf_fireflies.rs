//! Hard light transport at 1 spp: `covered-light` (light reaching the room only through gaps) and
//! `caustics` (a glass sphere focusing a small lamp). SVGF's output stays finite and its fireflies
//! do not spread into blotches: the worst 8x8 block's excess brightness over a 256-spp reference,
//! over the eighth to the thirty-second frame of a still camera and three seeds, stays bounded,
//! and below the per-frame filter's. SVGF holds them with its firefly clamp
//! (`SvgfParams::firefly_clamp`): without it, a caustic path's firefly lingers.

use lucid_engine::capture::{rec709_luminance, ImageData};
use lucid_engine::scene::builtin::{build_with, BuildOptions};
use lucid_passes::renderer::Settings;
use lucid_tests::svgf::{frame, reference, renderer, settings, with_firefly_clamp, Method, SIZE};
use lucid_tests::{assert_no_validation_messages, context};

/// The frames whose worst block counts: the eighth to the thirty-second (a network can pass one
/// frame by chance and blotch on the next, training/README.md "Four scales"; SVGF's clamp as
/// first shipped held frames 8-12 and let a caustic's firefly through at frame 29,
/// thirty-second session).
const FRAMES: std::ops::RangeInclusive<usize> = 8..=32;
/// The seeds of the random numbers rendered: a blotch is a rare event, and one seed can miss it (the
/// twenty-eighth session's weights passed at seed 0 at 0.378 and blotched at seed 1 at 1.162,
/// training/README.md, thirtieth session).
const SEEDS: [u32; 3] = [0, 1, 2];
/// Largest accepted worst-block excess over [`FRAMES`] and the seeds (measured: covered-light SVGF
/// 0.095, learned 0.196, per-frame filter 5.18; caustics SVGF 0.107 (5.66 without the clamp, at
/// seed 2), learned 0.070, per-frame filter 66).
const MAX_EXCESS_COVERED_LIGHT: f64 = 0.6;
const MAX_EXCESS_CAUSTICS: f64 = 0.25;
/// Side of the blocks whose mean error is compared.
const BLOCK: u32 = 8;

/// The largest excess of an 8x8 block's mean luminance over the reference's, relative to the
/// reference's mean luminance: a firefly smeared into a blotch brightens a whole block, while
/// the reference's own residual noise mostly averages out within one.
fn worst_block_excess(test: &ImageData, reference: &ImageData) -> f64 {
    let block_mean = |image: &ImageData, bx: u32, by: u32| {
        let sum: f64 = (by..by + BLOCK)
            .flat_map(|y| (bx..bx + BLOCK).map(move |x| (x, y)))
            .map(|(x, y)| f64::from(rec709_luminance(image.pixels[(y * SIZE + x) as usize])))
            .sum();
        sum / f64::from(BLOCK * BLOCK)
    };
    let mean: f64 = reference
        .pixels
        .iter()
        .map(|&p| f64::from(rec709_luminance(p)))
        .sum::<f64>()
        / reference.pixels.len() as f64;
    (0..SIZE / BLOCK)
        .flat_map(|by| (0..SIZE / BLOCK).map(move |bx| (bx * BLOCK, by * BLOCK)))
        .map(|(bx, by)| (block_mean(test, bx, by) - block_mean(reference, bx, by)) / mean)
        .fold(0.0, f64::max)
}

/// The worst block excess of each of `methods` over [`FRAMES`] of still sequences of `name`, one
/// a seed of `seeds`.
fn worst_errors<const N: usize>(name: &str, seeds: &[u32], methods: [Settings; N]) -> [f64; N] {
    let ctx = context(false);
    let scene = build_with(name, &BuildOptions { detail: 0.05 }).expect("scene");
    let reference = reference(&ctx, &scene, scene.camera, (16, 16), 8);
    let errors = methods.map(|method| {
        seeds
            .iter()
            .map(|&seed| {
                let seeded = Settings { seed, ..method };
                let mut r = renderer(&ctx, scene.clone(), seeded);
                (1..=*FRAMES.end())
                    .map(|t| (t, frame(&mut r)))
                    .filter(|(t, _)| FRAMES.contains(t))
                    .map(|(_, image)| worst_block_excess(&image, &reference))
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max)
    });
    assert_no_validation_messages(&ctx);
    errors
}

/// `denoiser` leaves no blotch above `max_excess` on scene `name` at any of `seeds`, nor one worse
/// than the per-frame filter's.
fn assert_no_blotches(name: &str, seeds: &[u32], denoiser: Method, max_excess: f64) {
    let [denoised, per_frame] = worst_errors(
        name,
        seeds,
        [settings(denoiser, 8), settings(Method::PerFrame, 8)],
    );
    eprintln!("{name} worst block excess: {denoiser:?} {denoised:.3}, per-frame {per_frame:.3}");
    assert!(
        denoised <= max_excess,
        "{denoiser:?}: a blotch: {denoised:.3}"
    );
    assert!(
        denoised <= per_frame,
        "{denoiser:?}: no worse than the per-frame filter"
    );
}

#[test]
fn covered_light_has_no_blotches() {
    assert_no_blotches(
        "covered-light",
        &SEEDS,
        Method::Svgf,
        MAX_EXCESS_COVERED_LIGHT,
    );
}

#[test]
fn learned_denoiser_leaves_no_blotches_on_covered_light() {
    assert_no_blotches(
        "covered-light",
        &SEEDS,
        Method::Neural,
        MAX_EXCESS_COVERED_LIGHT,
    );
}

#[test]
fn caustics_have_no_blotches() {
    assert_no_blotches("caustics", &SEEDS, Method::Svgf, MAX_EXCESS_CAUSTICS);
    assert_no_blotches("caustics", &SEEDS, Method::Neural, MAX_EXCESS_CAUSTICS);
}

/// The clamp is what holds SVGF's blotches: at seed 2 a caustic path through the glass brings a
/// firefly that SVGF without it keeps as a blotch for frames (measured 5.66).
#[test]
fn without_the_firefly_clamp_svgf_blotches() {
    let [unclamped] = worst_errors(
        "caustics",
        &[2],
        [with_firefly_clamp(settings(Method::Svgf, 8), false)],
    );
    eprintln!("caustics worst block excess: SVGF without the firefly clamp {unclamped:.3}");
    assert!(
        unclamped > 2.0 * MAX_EXCESS_CAUSTICS,
        "the clamp is what holds the blotch: {unclamped:.3} without it"
    );
}
