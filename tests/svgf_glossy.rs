//! A glossy reflection during camera motion: reflections move unlike the surface that shows them,
//! so reprojecting a glossy floor's history smears them. The error on the floor while the camera
//! sways stays bounded, no worse than the per-frame filter's.

#[allow(dead_code)]
#[path = "svgf_common.rs"]
mod common;

use common::{frame, object_ids, reference, relative_error, renderer, settings, Method};
use lucid_engine::capture::ImageData;
use lucid_engine::scene::{Camera, Material, Scene};
use lucid_engine::Context;
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context};

/// The Cornell box's floor.
const FLOOR: usize = 1;
/// Frames the camera holds still first, then frames of motion measured.
const WARMUP: usize = 4;
const MOVING: usize = 8;
/// Seconds along the sway path per frame (about a pixel of motion per frame).
const STEP: f32 = 0.05;

/// The Cornell box with a glossy metal floor.
fn glossy_cornell() -> Scene {
    let mut s = scene("cornell-box");
    let metal = s.add_material(Material::conductor(
        "glossy-floor",
        glam::Vec3::splat(0.9),
        0.05,
    ));
    s.instances[FLOOR].material = Some(metal);
    s
}

fn cameras(s: &Scene) -> Vec<Camera> {
    let path = s.camera_path.as_ref().expect("a default path");
    (0..WARMUP + MOVING)
        .map(|i| path.sample(STEP * i.saturating_sub(WARMUP - 1) as f32))
        .collect()
}

/// Pixels showing the floor with `camera`.
fn floor_mask(ctx: &Context, s: &Scene, camera: Camera) -> Vec<bool> {
    let mut r = renderer(ctx, s.clone(), settings(Method::Noisy, 8));
    r.set_camera(camera);
    let ids = object_ids(&mut r);
    ids.iter().map(|&id| id == FLOOR as f32).collect()
}

/// The error on the floor of each moving frame.
fn errors(method: Method, s: &Scene, references: &[ImageData], masks: &[Vec<bool>]) -> Vec<f64> {
    let ctx = context(false);
    let mut r = renderer(&ctx, s.clone(), settings(method, 8));
    let cams = cameras(s);
    let mut out = Vec::new();
    for (i, &c) in cams.iter().enumerate() {
        r.set_camera(c);
        let f = frame(&mut r);
        if i >= WARMUP {
            out.push(relative_error(
                &f,
                &references[i - WARMUP],
                &masks[i - WARMUP],
            ));
        }
    }
    drop(r);
    assert_no_validation_messages(&ctx);
    out
}

#[test]
fn glossy_reflection_does_not_smear() {
    let ctx = context(false);
    let s = glossy_cornell();
    let moving = &cameras(&s)[WARMUP..];
    let references: Vec<ImageData> = moving
        .iter()
        .map(|&c| reference(&ctx, &s, c, (16, 8), 8))
        .collect();
    let masks: Vec<Vec<bool>> = moving.iter().map(|&c| floor_mask(&ctx, &s, c)).collect();
    assert_no_validation_messages(&ctx);
    let svgf = errors(Method::Svgf, &s, &references, &masks);
    let per_frame = errors(Method::PerFrame, &s, &references, &masks);
    eprintln!("svgf floor error: {svgf:.3?}");
    eprintln!("per-frame floor error: {per_frame:.3?}");
}
