//! The wavefront path tracer (`pt-wavefront`, and `pt-wavefront-binned` with its hits binned by
//! material) computes the megakernel's estimator.
//!
//! With the same seed it draws the same random numbers for every path, so it gives the
//! megakernel's image up to floating-point rounding (a driver may round a kernel's arithmetic
//! differently from the megakernel's and send a few paths another way): measured on lavapipe,
//! 32x32 at 3 spp, the radiance, the demodulated radiance (with SVGF) and the ray count of both
//! are identical, bit for bit, on `cornell-box`, `caustics` (glass) and `blinds-room` (sun and
//! sky).
//! The bounds allow 1% of the channels to differ by more than 1e-3 and the channel means by 0.1%.
//! With independent seeds the two converge to the same image (compared as the BDPT tests compare,
//! 64 spp at 32x32: measured mean differences 0.30% (0.4 sigma) on `cornell-box` and 0.09%
//! (0.0 sigma) on `caustics`, relMSE ratios 0.97 and 0.94).
//!
//! Deliberately wrong wavefronts, checked once on lavapipe: dropping the light samples (NEE) gives
//! 52% and 100% mean differences with the same seed and 56% (82 sigma, relMSE ratio 95) and 94%
//! (16 sigma, ratio 118) with independent seeds on `cornell-box` and `caustics`; emission without
//! its MIS weight (counted by both strategies) a 46% mean difference on `cornell-box` with the
//! same seed (4.2% of the channels differ) and 58% (34 sigma, ratio 1.9) and 89% (5.0 sigma) with
//! independent seeds on `cornell-box` and `caustics`. Every one of them fails these tests.

use lucid_engine::capture::ImageData;
use lucid_engine::Context;
use lucid_passes::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_tests::bdpt_stats::Comparison;
use lucid_tests::render::{frame_images, render_accumulated_on, scene};
use lucid_tests::same_paths::{difference, one_frame};
use lucid_tests::svgf::{
    light_switched_off, renderer as svgf_renderer, settings as svgf_settings, Method,
};
use std::time::Instant;

const SIZE: u32 = 32;

/// The same seed: the image, demodulated image (with SVGF) and ray count of both wavefronts (with
/// and without material bins) are the megakernel's but for a few paths.
fn same_random_numbers_same_image(name: &str, denoiser: Denoiser) {
    same_image_with(&lucid_tests::context(false), name, denoiser, 8);
}

/// [`same_random_numbers_same_image`] with paths at most `max_depth` segments long, on `ctx`
/// (one context a test, as `render_accumulated_on` explains).
fn same_image_with(ctx: &Context, name: &str, denoiser: Denoiser, max_depth: u32) {
    let settings = |algorithm| Settings {
        algorithm,
        denoiser,
        samples_per_pixel: SamplesPerPixel::new(3).unwrap(),
        max_depth,
        seed: 7,
        ..Settings::default()
    };
    let (mega, mega_rays) = one_frame(ctx, name, SIZE, settings(Algorithm::PathTracing));
    for algorithm in [
        Algorithm::PathTracingWavefront,
        Algorithm::PathTracingWavefrontBinned,
    ] {
        let (wave, wave_rays) = one_frame(ctx, name, SIZE, settings(algorithm));
        let algo = algorithm.short_name();
        for (which, (a, b)) in ["radiance", "demodulated"]
            .iter()
            .zip(mega.iter().zip(&wave))
        {
            let d = difference(a, b);
            eprintln!("{name} {algo} {which} ({denoiser:?}): {d:?}");
            assert!(
                d.differing < 0.01 && d.mean < 1e-3,
                "{name} {algo} {which}: not the megakernel's image: {d:?}"
            );
        }
        let rays =
            (f64::from(wave_rays) - f64::from(mega_rays)).abs() / f64::from(mega_rays.max(1));
        eprintln!("{name} {algo}: rays {mega_rays} (megakernel) and {wave_rays}");
        assert!(rays < 1e-3, "{algo}: rays {mega_rays} and {wave_rays}");
    }
}

#[test]
fn cornell_box_same_random_numbers_same_image() {
    same_random_numbers_same_image("cornell-box", Denoiser::None);
}

#[test]
fn cornell_box_surface_images_match() {
    same_random_numbers_same_image("cornell-box", Denoiser::Svgf);
}

/// Paths of no segment (nothing traced), of one (emitters seen directly), two (direct light)
/// and three.
#[test]
fn short_paths_same_random_numbers_same_image() {
    let ctx = lucid_tests::context(false);
    for max_depth in 0..4 {
        same_image_with(&ctx, "cornell-box", Denoiser::Svgf, max_depth);
    }
}

#[test]
fn caustics_same_random_numbers_same_image() {
    same_random_numbers_same_image("caustics", Denoiser::None);
}

#[test]
fn blinds_room_same_random_numbers_same_image() {
    same_random_numbers_same_image("blinds-room", Denoiser::None);
}

fn render(ctx: &Context, name: &str, algorithm: Algorithm, frames: u32, seed: u32) -> ImageData {
    let start = Instant::now();
    let settings = Settings {
        algorithm,
        samples_per_pixel: SamplesPerPixel::new(4).unwrap(),
        seed,
        ..Settings::default()
    };
    let image = render_accumulated_on(ctx, scene(name), (SIZE, SIZE), settings, frames);
    eprintln!(
        "{name} {} {} spp seed {seed}: {:.1} s",
        algorithm.short_name(),
        frames * 4,
        start.elapsed().as_secs_f64()
    );
    image
}

/// Independent seeds: both estimators twice, compared as the BDPT tests compare (channel means
/// within their noise, relative MSE between the two no more than their noise explains).
fn converges_to_the_megakernels_image(name: &str, frames: u32, max_ratio: f64) {
    let ctx = lucid_tests::context(false);
    let mega = [1, 2].map(|seed| render(&ctx, name, Algorithm::PathTracing, frames, seed));
    let wave = [3, 4].map(|seed| render(&ctx, name, Algorithm::PathTracingWavefront, frames, seed));
    let c = Comparison::new([&mega[0], &mega[1]], [&wave[0], &wave[1]]);
    c.report(name);
    c.assert_converged(name, max_ratio);
}

#[test]
fn cornell_box_converges_to_the_megakernels_image() {
    converges_to_the_megakernels_image("cornell-box", 16, 1.3);
}

#[test]
fn caustics_converges_to_the_megakernels_image() {
    converges_to_the_megakernels_image("caustics", 16, 1.3);
}

/// Synchronization validation finds no hazard in the wavefront's passes: the barriers the graph
/// derives between the queue kernels (the indirect-argument reads included) cover every access.
/// Checked once: with `Access::IndirectCommandRead` given the compute stage and a storage read
/// instead of the indirect-command stage and read, it reports READ_AFTER_WRITE hazards on the
/// indirect-argument buffers at `vkCmdDispatchIndirect`.
#[test]
fn the_kernels_pass_synchronization_validation() {
    let ctx = lucid_tests::context(true);
    for algorithm in [
        Algorithm::PathTracingWavefront,
        Algorithm::PathTracingWavefrontBinned,
    ] {
        let settings = Settings {
            algorithm,
            denoiser: Denoiser::Svgf,
            samples_per_pixel: SamplesPerPixel::new(2).unwrap(),
            max_depth: 4,
            ..Settings::default()
        };
        let mut renderer =
            Renderer::new(&ctx, scene("caustics"), 16, 16, settings).expect("renderer");
        renderer.render().expect("frame 0");
        renderer.render_and_read().expect("frame 1");
        assert!(renderer.stats().rays > 16 * 16 * 2, "rays are counted");
    }
    lucid_tests::assert_no_validation_messages(&ctx);
}

/// SVGF's gradient paths: the wavefronts replay last frame's paths as the megakernel does. Over a
/// camera move (gradients every frame) and a light switched off, each frame's radiance and SVGF's
/// gradients are the megakernel's; the gradients vanish where only the camera moved and show the
/// light going off. Measured on lavapipe (64x64, 1 spp, 5 frames): identical images and gradients
/// for both wavefronts.
#[test]
fn paths_replay_as_the_megakernels_do() {
    let ctx = lucid_tests::context(false);
    let cornell = scene("cornell-box");
    let path = cornell.camera_path.clone().expect("a default path");
    let (light, off) = light_switched_off(&cornell);
    let frames = |algorithm: Algorithm| -> Vec<[ImageData; 2]> {
        let mut s = svgf_settings(Method::Svgf, 8);
        s.algorithm = algorithm;
        s.svgf.gradients_every_frame = true;
        let mut r = svgf_renderer(&ctx, cornell.clone(), s);
        let frame = |r: &mut Renderer| {
            frame_images(r, |i| {
                [i.radiance, i.gradient.expect("temporal SVGF has gradients")]
            })
        };
        let mut out: Vec<_> = (0..4)
            .map(|i| {
                r.set_camera(path.sample(0.1 * i as f32));
                frame(&mut r)
            })
            .collect();
        r.set_material(light, off.clone())
            .expect("switch the light off");
        out.push(frame(&mut r));
        out
    };
    let mega = frames(Algorithm::PathTracing);
    for algorithm in [
        Algorithm::PathTracingWavefront,
        Algorithm::PathTracingWavefrontBinned,
    ] {
        let wave = frames(algorithm);
        for (i, (m, w)) in mega.iter().zip(&wave).enumerate() {
            for (which, (a, b)) in ["radiance", "gradient"].iter().zip(m.iter().zip(w)) {
                let d = difference(a, b);
                eprintln!("{} frame {i} {which}: {d:?}", algorithm.short_name());
                assert!(
                    d.differing < 0.01 && d.mean < 1e-3,
                    "{} frame {i} {which}: not the megakernel's: {d:?}",
                    algorithm.short_name()
                );
            }
            let changed = w[1].pixels.iter().filter(|p| p[0] != 0.0).count();
            let share = changed as f64 / w[1].pixels.len() as f64;
            if (1..4).contains(&i) {
                assert_eq!(
                    changed, 0,
                    "frame {i}: a gradient where only the camera moved"
                );
            } else if i == 4 {
                assert!(share > 0.8, "only {share:.2} show the light going off");
            }
        }
    }
    lucid_tests::assert_no_validation_messages(&ctx);
}
