//! A light switched off: SVGF's output darkens within 4 frames because the temporal gradients
//! reject the history; without them the moving average lags for many frames. A light switched on:
//! SVGF's firefly clamp, which bounds a sample by the history around it, lets the new light in as
//! fast as the moving average without the clamp would.

use lucid_tests::render::scene;
use lucid_tests::svgf::{
    everywhere, frame, light_switched_off, mean_luminance, renderer, settings, with_firefly_clamp,
    Method,
};
use lucid_tests::{assert_no_validation_messages, context};

/// Frames rendered before the switch (the history fills) and after it.
const BEFORE: usize = 8;
const AFTER: usize = 4;
/// The largest accepted brightness 4 frames after the switch, relative to before (the reference
/// is black: the box has no other light).
const MAX_REMAINING: f64 = 0.05;

/// The least brightness, relative to the moving average's without the firefly clamp, that SVGF with
/// the clamp reaches in each of the 4 frames after a light is switched on.
const MIN_SWITCH_ON_RATIO: f64 = 0.95;

/// Mean luminance of the frames after the light goes off, relative to the last frame before.
fn remaining_brightness(method: Method) -> Vec<f64> {
    let ctx = context(false);
    let cornell = scene("cornell-box");
    let (light, off) = light_switched_off(&cornell);
    let mut r = renderer(&ctx, cornell, settings(method, 8));
    let all = everywhere();
    let mut before = 0.0;
    for _ in 0..BEFORE {
        before = mean_luminance(&frame(&mut r), &all);
    }
    r.set_material(light, off).expect("switch the light off");
    let remaining = (0..AFTER)
        .map(|_| mean_luminance(&frame(&mut r), &all) / before)
        .collect();
    drop(r);
    assert_no_validation_messages(&ctx);
    remaining
}

#[test]
fn the_image_darkens_within_four_frames() {
    let remaining = remaining_brightness(Method::Svgf);
    eprintln!("with gradients: {remaining:.3?}");
    assert!(
        remaining[AFTER - 1] <= MAX_REMAINING,
        "{:.3} of the brightness remains 4 frames after the switch",
        remaining[AFTER - 1]
    );
}

#[test]
fn without_gradients_the_history_lags() {
    let remaining = remaining_brightness(Method::SvgfWithoutGradients);
    eprintln!("without gradients: {remaining:.3?}");
    assert!(
        remaining[AFTER - 1] > 2.0 * MAX_REMAINING,
        "the gradients are what makes the image darken: {:.3} remains without them",
        remaining[AFTER - 1]
    );
}

#[test]
fn the_learned_denoiser_darkens_within_four_frames() {
    let remaining = remaining_brightness(Method::Neural);
    eprintln!("learned denoiser: {remaining:.3?}");
    assert!(
        remaining[AFTER - 1] <= MAX_REMAINING,
        "{:.3} of the brightness remains 4 frames after the switch",
        remaining[AFTER - 1]
    );
}

/// Mean luminance of the 4 frames after the Cornell box's light, off for 8 frames, is switched on,
/// by SVGF without temporal gradients (nothing but the moving average lets the light in) with the
/// firefly clamp on or off.
fn brightness_after_switch_on(firefly_clamp: bool) -> Vec<f64> {
    let ctx = context(false);
    let cornell = scene("cornell-box");
    let (light, off) = light_switched_off(&cornell);
    let on = cornell.materials[light].clone();
    let clamped = with_firefly_clamp(settings(Method::SvgfWithoutGradients, 8), firefly_clamp);
    let mut r = renderer(&ctx, cornell, clamped);
    r.set_material(light, off).expect("switch the light off");
    for _ in 0..BEFORE {
        frame(&mut r);
    }
    r.set_material(light, on).expect("switch the light on");
    let all = everywhere();
    let brightness = (0..AFTER)
        .map(|_| mean_luminance(&frame(&mut r), &all))
        .collect();
    drop(r);
    assert_no_validation_messages(&ctx);
    brightness
}

#[test]
fn the_firefly_clamp_lets_a_light_switched_on_in() {
    let clamped = brightness_after_switch_on(true);
    let unclamped = brightness_after_switch_on(false);
    let ratios: Vec<f64> = clamped.iter().zip(&unclamped).map(|(c, u)| c / u).collect();
    eprintln!("brightness after the switch with the clamp, relative to without: {ratios:.3?}");
    assert!(
        unclamped[AFTER - 1] > 2.0 * unclamped[0],
        "the light comes in over several frames without gradients: {unclamped:.3?}"
    );
    for ratio in ratios {
        assert!(
            ratio >= MIN_SWITCH_ON_RATIO,
            "the clamp holds the new light back: {ratio:.3} of the brightness without it"
        );
    }
}
