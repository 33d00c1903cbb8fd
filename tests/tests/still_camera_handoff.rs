//! The temporal denoisers' still-camera hand-off (`passes/src/denoise/handoff`): while the camera
//! moves, and for the first [`Handoff::first_frames`] still frames, it leaves the denoised image as
//! it is, bit for bit; after that the image keeps converging past the denoiser's plateau, towards
//! plain accumulation of the same samples. For the learned denoiser and for SVGF's temporal mode,
//! each with its own [`Handoff`].

use lucid_engine::capture::ImageData;
use lucid_passes::denoise::handoff::Handoff;
use lucid_passes::renderer::{Denoiser, Settings};
use lucid_tests::render::scene;
use lucid_tests::svgf::{everywhere, frame, reference, relative_error, renderer, settings, Method};
use lucid_tests::{assert_no_validation_messages, context};

/// `method`'s settings (a temporal denoiser) with or without accumulation.
fn denoised(method: Method, accumulate: bool) -> Settings {
    Settings {
        accumulate,
        ..settings(method, 8)
    }
}

/// The images of a camera moving along the Cornell box's path, without and with accumulation.
fn moving_frames(method: Method) -> [Vec<ImageData>; 2] {
    let ctx = context(false);
    let cornell = scene("cornell-box");
    let path = cornell.camera_path.clone().expect("a default path");
    let frames = [false, true].map(|accumulate| {
        let mut r = renderer(&ctx, cornell.clone(), denoised(method, accumulate));
        (0..3)
            .map(|i| {
                r.set_camera(path.sample(0.1 * i as f32));
                frame(&mut r)
            })
            .collect()
    });
    assert_no_validation_messages(&ctx);
    frames
}

#[test]
fn a_moving_camera_gets_the_denoised_image_unchanged() {
    for method in [Method::Neural, Method::Svgf] {
        let [alone, accumulating] = moving_frames(method);
        for (i, (alone, accumulating)) in alone.iter().zip(&accumulating).enumerate() {
            assert!(
                alone.pixels == accumulating.pixels,
                "{method:?}, frame {i}: the moving camera's image differs with accumulation on"
            );
        }
    }
}

/// The errors relative to a reference of the Cornell box after `2 * handoff.first_frames` still
/// frames: with the hand-off, `method` alone, and plain accumulation. Checks that the last frame
/// before the hand-off starts is `method`'s image unchanged.
fn still_errors(method: Method, handoff: Handoff) -> [f64; 3] {
    let ctx = context(false);
    let cornell = scene("cornell-box");
    let camera = cornell.camera;
    let truth = reference(&ctx, &cornell, camera, (64, 16), 8);
    let all = everywhere();
    let first = handoff.first_frames as usize;
    // The last frame before the hand-off starts, and the error of the last, fully faded in.
    let error_after = |settings: Settings| {
        let mut r = renderer(&ctx, cornell.clone(), settings);
        r.set_camera(camera);
        let mut before = None;
        let mut last = None;
        for i in 1..=2 * first {
            let image = frame(&mut r);
            if i == first {
                before = Some(image);
            } else {
                last = Some(image);
            }
        }
        let (before, last) = (before.expect("a frame"), last.expect("frames"));
        (before, relative_error(&last, &truth, &all))
    };
    let (handoff_before, with_handoff) = error_after(denoised(method, true));
    let (plateau_before, plateau) = error_after(denoised(method, false));
    let (_, accumulation) = error_after(Settings {
        denoiser: Denoiser::None,
        ..denoised(method, true)
    });
    assert_no_validation_messages(&ctx);
    eprintln!(
        "{method:?}: relative error after {} still frames: hand-off {with_handoff:.4}, \
         denoiser alone {plateau:.4}, accumulation alone {accumulation:.4}",
        2 * first
    );
    assert!(
        handoff_before.pixels == plateau_before.pixels,
        "{method:?}: still frame {first} (before the hand-off starts) is not the denoised image"
    );
    [with_handoff, plateau, accumulation]
}

/// Checks that `method`'s image after its still frames has under `below_plateau` times the error
/// of `method` alone and under `near_accumulation` times plain accumulation's.
fn assert_converges(method: Method, handoff: Handoff, below_plateau: f64, near_accumulation: f64) {
    let [with_handoff, plateau, accumulation] = still_errors(method, handoff);
    assert!(
        with_handoff < below_plateau * plateau,
        "{method:?}: the hand-off ({with_handoff:.4}) does not improve on the plateau ({plateau:.4})"
    );
    assert!(
        with_handoff < near_accumulation * accumulation,
        "{method:?}: the hand-off ({with_handoff:.4}) stays far from plain accumulation \
         ({accumulation:.4})"
    );
}

#[test]
fn the_learned_denoiser_converges_past_its_plateau() {
    // Measured on lavapipe with the emission supersampled at the light's edges (the learned
    // denoiser's default): hand-off 0.0393, the denoiser alone 0.0525, accumulation 0.0526. The
    // pass took most of the denoiser's own error away (0.1303 without it, when the hand-off had
    // 0.0619 and these bounds were 0.6 and 1.3), so the hand-off has less to gain over the
    // plateau and must now beat plain accumulation outright.
    assert_converges(Method::Neural, Handoff::NEURAL, 0.8, 0.85);
}

#[test]
fn svgf_converges_past_its_plateau() {
    // Measured on lavapipe after 32 frames: hand-off 0.0659, SVGF alone 0.0944, accumulation
    // 0.0688 (SVGF's blur is its error: a margin of 1 hands over as soon as the accumulation
    // beats it, so the hand-off passes accumulation early).
    assert_converges(Method::Svgf, Handoff::SVGF, 0.8, 1.05);
}
