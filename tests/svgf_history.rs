//! SVGF's histories: the temporal gradients are exactly zero when only the camera moves (the
//! re-traced paths match the path tracer's bit for bit), and a resize or a history reset starts
//! the histories afresh without a stale frame showing.

#[allow(dead_code)]
#[path = "svgf_common.rs"]
mod common;

use common::{frame, mean_luminance, renderer, settings, Method};
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context};

#[test]
fn gradients_vanish_when_only_the_camera_moves() {
    let ctx = context(false);
    let cornell = scene("cornell-box");
    let path = cornell.camera_path.clone().expect("a default path");
    let mut outputs = Vec::new();
    for method in [Method::Svgf, Method::SvgfWithoutGradients] {
        let mut s = settings(method, 8);
        s.svgf.gradients_every_frame = true;
        let mut r = renderer(&ctx, cornell.clone(), s);
        let frames: Vec<_> = (0..6)
            .map(|i| {
                r.set_camera(path.sample(0.1 * i as f32));
                frame(&mut r)
            })
            .collect();
        outputs.push(frames);
    }
    assert_no_validation_messages(&ctx);
    assert_eq!(
        outputs[0], outputs[1],
        "a gradient appeared where only the camera moved: the re-traced paths differ from the path tracer's"
    );
}

#[test]
fn resize_and_reset_start_afresh() {
    let ctx = context(false);
    let mut r = renderer(&ctx, scene("cornell-box"), settings(Method::Svgf, 8));
    for _ in 0..4 {
        frame(&mut r);
    }
    r.resize(48, 40).expect("resize");
    let resized = frame(&mut r);
    assert_eq!((resized.width, resized.height), (48, 40));
    let all = vec![true; 48 * 40];
    let resized_mean = mean_luminance(&resized, &all);
    r.executor_mut().reset_history();
    let reset_mean = mean_luminance(&frame(&mut r), &all);
    // The brightness the history converges to at the new size (a single frame's mean varies by
    // about 12% at 1 spp: the light covers few pixels).
    let settled = (0..6)
        .map(|_| mean_luminance(&frame(&mut r), &all))
        .sum::<f64>()
        / 6.0;
    drop(r);
    assert_no_validation_messages(&ctx);
    for (what, mean) in [("resize", resized_mean), ("reset", reset_mean)] {
        assert!(
            (mean / settled - 1.0).abs() < 0.25,
            "after a {what} the image has the settled brightness: {mean:.4} vs {settled:.4}"
        );
    }
}
