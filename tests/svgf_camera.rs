//! SVGF under camera motion: a pan and dolly across `classroom` flickers far less than the
//! a-trous filter applied per frame.

#[allow(dead_code)]
#[path = "svgf_common.rs"]
mod common;

use common::{frame, reference, renderer, settings, Method};
use glam::Vec3;
use lucid_engine::capture::{ImageData, PngEncoding};
use lucid_engine::metrics::evaluate_sequence;
use lucid_engine::scene::builtin::{build_with, BuildOptions};
use lucid_engine::scene::{Camera, CameraKey, CameraPath, PathInterpolation, Scene};
use lucid_tests::{assert_no_validation_messages, context};

/// Frames the camera holds still first (the histories fill), then frames of motion measured.
const WARMUP: usize = 8;
const MOVING: usize = 8;
/// Longest path: direct light and one indirect bounce.
const MAX_DEPTH: u32 = 2;

fn classroom() -> Scene {
    build_with("classroom", &BuildOptions { detail: 0.05 }).expect("classroom")
}

/// The start of the classroom's default dolly with the target panning sideways.
fn pan_and_dolly(scene: &Scene) -> CameraPath {
    let keys = scene.camera_path.as_ref().expect("a default path").keys();
    let (first, last) = (keys[0], keys[keys.len() - 1]);
    let along = (last.position - first.position).length();
    let side = (first.target - first.position).cross(Vec3::Y).normalize() * 0.0012 * along;
    let at = |time: f32, f: f32, pan: f32| CameraKey {
        time,
        position: first.position.lerp(last.position, f),
        target: first.target + side * pan,
        ..first
    };
    let span = MOVING as f32
        * std::env::var("MS")
            .map(|v| v.parse::<f32>().unwrap())
            .unwrap_or(1.0);
    CameraPath::new(
        vec![at(0.0, 0.0, -1.0), at(span, 0.004, 1.0)],
        PathInterpolation::Linear,
    )
    .expect("valid keys")
}

/// The camera of each frame: still for `WARMUP` frames, then along the path.
fn cameras(scene: &Scene) -> Vec<Camera> {
    let path = pan_and_dolly(scene);
    (0..WARMUP + MOVING)
        .map(|i| path.sample(i.saturating_sub(WARMUP - 1) as f32))
        .collect()
}

fn sequence(method: Method) -> Vec<ImageData> {
    let ctx = context(false);
    let scene = classroom();
    let cameras = cameras(&scene);
    let mut r = renderer(&ctx, scene, settings(method, MAX_DEPTH));
    let frames = cameras
        .iter()
        .map(|&c| {
            r.set_camera(c);
            frame(&mut r)
        })
        .collect();
    drop(r);
    assert_no_validation_messages(&ctx);
    frames
}

#[test]
fn temporal_filter_flickers_a_fifth_of_the_per_frame_filter() {
    let ctx = context(false);
    let scene = classroom();
    let measured = WARMUP - 1..WARMUP + MOVING;
    let references: Vec<ImageData> = cameras(&scene)[measured.clone()]
        .iter()
        .map(|&c| reference(&ctx, &scene, c, (16, 8), MAX_DEPTH))
        .collect();
    assert_no_validation_messages(&ctx);
    let display = PngEncoding::default();
    let evaluate = |method| {
        let frames = sequence(method);
        let m = evaluate_sequence(&frames[measured.clone()], &references, &display).unwrap();
        for (i, f) in frames.iter().enumerate() {
            lucid_engine::capture::save_png(format!("/tmp/cam_{method:?}_{i:02}.png"), f, &display)
                .unwrap();
        }
        for (i, f) in references.iter().enumerate() {
            lucid_engine::capture::save_png(format!("/tmp/cam_ref_{:02}.png", i + 3), f, &display)
                .unwrap();
        }
        eprintln!("{method:?}: {:?}", m.mean);
        let change = |fr: &[ImageData]| -> f64 {
            let lum = |p: [f32; 4]| f64::from(lucid_engine::capture::rec709_luminance(p));
            let mean: f64 = fr[0].pixels.iter().map(|&p| lum(p)).sum::<f64>() / 4096.0;
            fr.windows(2)
                .map(|w| {
                    w[0].pixels
                        .iter()
                        .zip(&w[1].pixels)
                        .map(|(&a, &b)| (lum(a) - lum(b)).abs())
                        .sum::<f64>()
                        / 4096.0
                        / mean
                })
                .sum::<f64>()
                / (fr.len() - 1) as f64
        };
        {
            let lum = |p: [f32; 4]| lucid_engine::capture::rec709_luminance(p);
            let f = &frames[measured.clone()];
            for k in [2usize, 5] {
                let px: Vec<[f32; 4]> = (0..4096)
                    .map(|i| {
                        let d = ((lum(f[k + 1].pixels[i]) - lum(f[k].pixels[i]))
                            - (lum(references[k + 1].pixels[i]) - lum(references[k].pixels[i])))
                        .abs()
                            * 4.0;
                        [d, d, d, 1.0]
                    })
                    .collect();
                let img = ImageData::from_pixels(64, 64, px).unwrap();
                lucid_engine::capture::save_png(
                    format!("/tmp/inst_{method:?}_{k}.png"),
                    &img,
                    &PngEncoding::default(),
                )
                .unwrap();
            }
        }
        eprintln!(
            "self change {method:?} {:.3} ref {:.3}",
            change(&frames[measured.clone()]),
            change(&references)
        );
        m.mean
    };
    let per_frame = evaluate(Method::PerFrame);
    let svgf = evaluate(Method::Svgf);
    let noisy = evaluate(Method::Noisy);
    evaluate(Method::SvgfWithoutGradients);
    let ratio = svgf.temporal_instability / per_frame.temporal_instability;
    eprintln!(
        "instability ratio {ratio:.3}, noisy {:.3}",
        noisy.temporal_instability
    );
    assert!(ratio <= 0.2, "instability ratio {ratio:.3} > 1/5");
}
