//! The split view on the GPU (lavapipe in CI, synchronization validation on): each half comes
//! from its own configuration, both follow the camera, and moving it restarts both.

use super::{split_column, FrameRequest, FrameSource, RendererSource};
use crate::settings::{Denoiser, DisplaySettings, RenderSettings};
use lucid_engine::capture::ImageData;
use lucid_engine::graph::RenderGraph;
use lucid_engine::scene::{builtin, Camera};
use lucid_engine::{Context, ContextDesc};
use lucid_passes::debug::debug_view::View;

const SIZE: [u32; 2] = [48, 32];

/// Renders one frame through `source` and reads it back tone-mapped, as the app shows it.
fn frame(
    source: &mut RendererSource,
    camera: &Camera,
    left: &RenderSettings,
    right: &RenderSettings,
) -> ImageData {
    let mut graph = RenderGraph::new();
    let request = FrameRequest {
        camera,
        settings: left,
        extent: SIZE,
        time: 0.0,
        split: Some(right),
    };
    let hdr = source.render(&mut graph, &request).unwrap();
    let encoding = DisplaySettings::default().png_encoding();
    let ldr = lucid_passes::post::tonemap::add_tonemap(&mut graph, hdr, SIZE[0], SIZE[1], encoding);
    let readback = graph.readback(ldr);
    let executor = source.executor();
    let id = executor.execute(graph.compile().unwrap()).unwrap();
    executor.wait(id).unwrap().image(readback).unwrap()
}

/// Pixels of a depth view are grey; the Cornell box in colour has red and green walls.
fn grey_fraction(image: &ImageData, columns: std::ops::Range<u32>) -> f64 {
    let pixels: Vec<[f32; 4]> = (0..image.height)
        .flat_map(|y| columns.clone().map(move |x| (x, y)))
        .map(|(x, y)| image.pixels[(y * image.width + x) as usize])
        .collect();
    let grey = pixels
        .iter()
        .filter(|p| (p[0] - p[1]).abs() < 1e-4 && (p[1] - p[2]).abs() < 1e-4)
        .count();
    grey as f64 / pixels.len() as f64
}

#[test]
fn each_half_shows_its_configuration_and_both_follow_the_camera() {
    let ctx = Context::new(&ContextDesc::for_tests(true)).unwrap();
    let scene = builtin::build("cornell-box").unwrap();
    let mut camera = scene.camera;
    let mut source = RendererSource::new(&ctx, scene, SIZE).unwrap();
    let left = RenderSettings {
        denoiser: Denoiser::None,
        ..RenderSettings::default()
    };
    let right = RenderSettings {
        view: View::Depth,
        ..left.compared()
    };
    let split = split_column(SIZE[0]);
    let mut image = frame(&mut source, &camera, &left, &right);
    for _ in 0..2 {
        image = frame(&mut source, &camera, &left, &right);
    }
    let samples = |source: &RendererSource| source.split_stats().map(|s| s.map(|h| h.samples));
    assert_eq!(samples(&source), Some([3, 3]), "both halves accumulate");
    let left_grey = grey_fraction(&image, 0..split);
    let right_grey = grey_fraction(&image, split..SIZE[0]);
    assert!(left_grey < 0.5, "the left half is in colour ({left_grey})");
    assert_eq!(right_grey, 1.0, "the right half is the depth view");

    camera.position.x += 0.2;
    let moved = frame(&mut source, &camera, &left, &right);
    assert_eq!(
        samples(&source),
        Some([1, 1]),
        "moving the camera restarts both"
    );
    let changed = |columns: std::ops::Range<u32>| {
        columns
            .flat_map(|x| (0..SIZE[1]).map(move |y| (y * SIZE[0] + x) as usize))
            .filter(|&i| (image.pixels[i][0] - moved.pixels[i][0]).abs() > 0.05)
            .count()
    };
    let (left_changed, right_changed) = (changed(0..split), changed(split..SIZE[0]));
    println!(
        "grey: left {left_grey:.3}, right {right_grey:.3}; pixels changed by the move: left \
         {left_changed}, right {right_changed} of {}",
        split * SIZE[1]
    );
    assert!(
        left_changed > 20,
        "the left half moved ({left_changed} pixels)"
    );
    assert!(
        right_changed > 20,
        "the right half moved ({right_changed} pixels)"
    );

    drop(source);
    let messages = ctx.validation_log().take();
    assert!(messages.is_empty(), "validation: {messages:?}");
}
