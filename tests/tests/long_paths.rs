//! Long paths parked and continued over a compacted list (`Settings::park_long_paths`, one sample
//! a pixel) compute the one kernel's image, and with SVGF its demodulated image: the path tracer's
//! and BDPT's camera subpaths.
//!
//! The parked paths keep their random numbers, so with the same seed both give the same image but
//! for the order in which a path's contributions are summed: measured on lavapipe, 48x48 at one
//! sample, the ray counts are equal and no channel differs by more than 1e-3 (relative) on
//! `cornell-box`, `caustics` and `blinds-room` (channel means within 1e-9), and BDPT's the same on
//! `cornell-box` and `blinds-room`. Continuations whose radiance is dropped (checked once on
//! lavapipe) move the channel means by 2.9%, 0.39% and 11% there, BDPT's by 0.57% and 17%, and
//! fail the bounds.

use lucid_passes::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_tests::render::scene;
use lucid_tests::same_paths::{difference, one_frame};

const SIZE: u32 = 48;

fn settings(park_long_paths: bool) -> Settings {
    Settings {
        park_long_paths,
        seed: 11,
        ..Settings::default()
    }
}

fn parked_paths_same_image(name: &str, algorithm: Algorithm, denoiser: Denoiser) {
    let ctx = lucid_tests::context(false);
    let with = |park| Settings {
        algorithm,
        denoiser,
        ..settings(park)
    };
    let (one, one_rays) = one_frame(&ctx, name, SIZE, with(false));
    let (parked, parked_rays) = one_frame(&ctx, name, SIZE, with(true));
    assert_eq!(one_rays, parked_rays, "{name}: the same rays");
    assert_eq!(one.len(), parked.len());
    for (which, (a, b)) in ["radiance", "demodulated"]
        .iter()
        .zip(one.iter().zip(&parked))
    {
        let d = difference(a, b);
        eprintln!("{name} {which} ({algorithm:?}, {denoiser:?}): {d:?}, rays {one_rays} and {parked_rays}");
        assert!(
            d.differing < 1e-3 && d.mean < 1e-5,
            "{name} {which}: not the one kernel's image: {d:?}"
        );
    }
}

#[test]
fn cornell_box_parked_paths_same_image() {
    parked_paths_same_image("cornell-box", Algorithm::PathTracing, Denoiser::None);
}

#[test]
fn cornell_box_parked_paths_same_surface_images() {
    parked_paths_same_image("cornell-box", Algorithm::PathTracing, Denoiser::Svgf);
}

#[test]
fn caustics_parked_paths_same_image() {
    parked_paths_same_image("caustics", Algorithm::PathTracing, Denoiser::None);
}

#[test]
fn blinds_room_parked_paths_same_image() {
    parked_paths_same_image("blinds-room", Algorithm::PathTracing, Denoiser::None);
}

#[test]
fn cornell_box_parked_camera_subpaths_same_image() {
    parked_paths_same_image("cornell-box", Algorithm::Bidirectional, Denoiser::None);
}

#[test]
fn cornell_box_parked_camera_subpaths_same_surface_images() {
    parked_paths_same_image("cornell-box", Algorithm::Bidirectional, Denoiser::Svgf);
}

#[test]
fn blinds_room_parked_camera_subpaths_same_image() {
    parked_paths_same_image("blinds-room", Algorithm::Bidirectional, Denoiser::None);
}

/// The frame parks long paths only where it can: one sample a pixel, at most 1920x1080 pixels (128
/// MiB of records) and the setting on.
#[test]
fn parking_runs_only_with_one_sample_a_pixel() {
    let ctx = lucid_tests::context(false);
    let runs_at = |(width, height), settings: Settings| {
        let mut renderer =
            Renderer::new(&ctx, scene("cornell-box"), width, height, settings).unwrap();
        let plan = renderer.frame_plan().unwrap();
        let has = |suffix| plan.passes.iter().any(|p| p.name.ends_with(suffix));
        let continued = has(".long");
        assert_eq!(
            continued,
            has(".long_list"),
            "listed and continued together"
        );
        continued
    };
    let runs = |settings| runs_at((16, 16), settings);
    assert!(runs(settings(true)));
    assert!(runs_at((1920, 1080), settings(true)));
    assert!(!runs_at((1920, 1200), settings(true)));
    assert!(!runs(settings(false)));
    assert!(!runs(Settings {
        samples_per_pixel: SamplesPerPixel::new(2).unwrap(),
        ..settings(true)
    }));
    assert!(runs(Settings {
        denoiser: Denoiser::Svgf,
        ..settings(true)
    }));
    assert!(runs(Settings {
        algorithm: Algorithm::Bidirectional,
        ..settings(true)
    }));
    assert!(!runs(Settings {
        algorithm: Algorithm::Bidirectional,
        ..settings(false)
    }));
}
