//! The G-buffer: depth, normals and ids are sane, and motion vectors follow the camera and moved
//! instances (reprojection lands on the same object).

use std::f32::consts::FRAC_PI_2;

use glam::{Affine3A, Quat, Vec3};
use lucid_engine::capture::ImageData;
use lucid_engine::graph::RenderGraph;
use lucid_engine::scene::Camera;
use lucid_passes::renderer::{Renderer, Settings};
use lucid_tests::render::{frame_images, scene};
use lucid_tests::{assert_no_validation_messages, context, run};

struct Frame {
    depth: ImageData,
    normal: ImageData,
    ids: ImageData,
    motion: ImageData,
}

fn gbuffer_frame(renderer: &mut Renderer) -> Frame {
    let [depth, normal, ids, motion] = frame_images(renderer, |images| {
        let gb = &images.gbuffer;
        [gb.depth, gb.normal_roughness, gb.ids, gb.motion]
    });
    Frame {
        depth,
        normal,
        ids,
        motion,
    }
}

const SIZE: u32 = 48;

#[test]
fn static_frames_have_zero_motion_and_sane_geometry() {
    let ctx = context(false);
    let mut renderer =
        Renderer::new(&ctx, scene("cornell-box"), SIZE, SIZE, Settings::default()).unwrap();
    gbuffer_frame(&mut renderer);
    let f = gbuffer_frame(&mut renderer);
    for (i, m) in f.motion.pixels.iter().enumerate() {
        assert!(
            m[0].abs() < 1e-2 && m[1].abs() < 1e-2,
            "pixel {i} moved without motion: {m:?}"
        );
    }
    let hits = f.ids.pixels.iter().filter(|p| p[3] == 1.0).count();
    assert!(
        hits as u32 > SIZE * SIZE * 9 / 10,
        "the Cornell box fills the view: {hits}"
    );
    for (d, n) in f
        .depth
        .pixels
        .iter()
        .zip(&f.normal.pixels)
        .filter(|(d, _)| d[0] > 0.0)
    {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-2, "unit normals: {n:?}");
        assert!(d[0] > 1.0 && d[0] < 10.0, "depth in the box: {d:?}");
    }
    drop(renderer);
    assert_no_validation_messages(&ctx);
}

#[test]
fn a_moved_instance_has_motion_and_the_rest_does_not() {
    let ctx = context(false);
    let cornell = scene("cornell-box");
    let mut renderer = Renderer::new(&ctx, cornell, SIZE, SIZE, Settings::default()).unwrap();
    let before = gbuffer_frame(&mut renderer);
    // The instance seen at the image centre (one of the boxes) moves right by 0.1.
    let centre = before.ids.get(SIZE / 2, SIZE * 3 / 4).unwrap()[0] as usize;
    let transform = renderer.scene().instances[centre].transform;
    renderer
        .set_instance_transform(
            centre,
            Affine3A::from_translation(Vec3::new(0.1, 0.0, 0.0)) * transform,
        )
        .unwrap();
    let after = gbuffer_frame(&mut renderer);
    let mut moved = 0;
    for (i, (id, m)) in after
        .ids
        .pixels
        .iter()
        .zip(&after.motion.pixels)
        .enumerate()
    {
        if id[3] != 1.0 {
            continue;
        }
        if id[0] as usize == centre {
            // Moving right on screen means last frame's position is to the left.
            assert!(m[0] < -0.5, "pixel {i} of the moved box: {m:?}");
            moved += 1;
        } else {
            assert!(
                m[0].abs() < 1e-2 && m[1].abs() < 1e-2,
                "pixel {i} of a static object: {m:?}"
            );
        }
    }
    assert!(moved > 10, "the moved box covers pixels: {moved}");
    drop(renderer);
    assert_no_validation_messages(&ctx);
}

#[test]
fn camera_motion_reprojects_onto_the_same_objects() {
    let ctx = context(false);
    let mut renderer =
        Renderer::new(&ctx, scene("cornell-box"), SIZE, SIZE, Settings::default()).unwrap();
    let before = gbuffer_frame(&mut renderer);
    let mut camera = renderer.camera();
    camera.position += Vec3::new(0.15, 0.05, 0.0);
    renderer.set_camera(camera);
    let after = gbuffer_frame(&mut renderer);
    let (mut landed, mut same, mut moved) = (0, 0, 0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let m = after.motion.get(x, y).unwrap();
            let id = after.ids.get(x, y).unwrap();
            if id[3] != 1.0 {
                continue;
            }
            moved += usize::from(m[0].abs() > 0.5);
            let (px, py) = ((x as f32 + m[0]).round(), (y as f32 + m[1]).round());
            if px < 0.0 || py < 0.0 || px >= SIZE as f32 || py >= SIZE as f32 {
                continue;
            }
            landed += 1;
            let prev_id = before.ids.get(px as u32, py as u32).unwrap();
            same += usize::from(prev_id[0] == id[0]);
        }
    }
    assert!(
        moved > (SIZE * SIZE / 2) as usize,
        "a camera move shows in the motion vectors: {moved}"
    );
    assert!(
        same * 100 >= landed * 95,
        "{same} of {landed} reprojected pixels land on the same object"
    );
    drop(renderer);
    assert_no_validation_messages(&ctx);
}

/// The G-buffer of a frame seen from `now` after one seen from `before`: every motion vector is
/// finite and at most the shader's limit (half precision holds 65504 at most, and a GPU may store
/// a larger offset as infinity, which turns reprojection arithmetic into NaN), and the pixels that
/// lay at or behind the last camera's plane, where projecting is meaningless (mirrored, or
/// infinite at the plane), reproject off the frame. Returns how many pixels lay there.
fn check_motion_after(before: Camera, now: Camera, size: u32) -> usize {
    const MOTION_LIMIT: f32 = 32768.0;
    let ctx = context(false);
    let mut renderer =
        Renderer::new(&ctx, scene("cornell-box"), size, size, Settings::default()).unwrap();
    renderer.set_camera(before);
    gbuffer_frame(&mut renderer);
    renderer.set_camera(now);
    let after = gbuffer_frame(&mut renderer);
    let mut behind = 0;
    for y in 0..size {
        for x in 0..size {
            let m = after.motion.get(x, y).unwrap();
            assert!(
                m[0].abs() <= MOTION_LIMIT && m[1].abs() <= MOTION_LIMIT,
                "pixel ({x}, {y}): motion {m:?}"
            );
            if after.ids.get(x, y).unwrap()[3] != 1.0 || m[2] > 0.0 {
                continue;
            }
            behind += 1;
            let (px, py) = (x as f32 + m[0], y as f32 + m[1]);
            assert!(
                px < -0.5 || py < -0.5 || px >= size as f32 || py >= size as f32,
                "pixel ({x}, {y}) lay behind the last camera, yet reprojects to ({px}, {py})"
            );
        }
    }
    drop(renderer);
    assert_no_validation_messages(&ctx);
    behind
}

/// A dolly backwards: the walls beside the camera are seen now but lay behind the last camera.
#[test]
fn a_dolly_backwards_reprojects_what_was_behind_off_the_frame() {
    let s = scene("cornell-box");
    let mut inside = s.camera;
    inside.position = s.bounds().center();
    assert!(
        check_motion_after(inside, s.camera, SIZE) > 0,
        "nothing lay behind"
    );
}

/// A quarter turn: what the middle column (of an odd width) sees now lay on the last camera's
/// plane, give or take rounding, where the projection is infinite.
#[test]
fn a_quarter_turn_keeps_motion_finite() {
    let start = scene("cornell-box").camera;
    let mut turned = start;
    turned.orientation = Quat::from_axis_angle(start.up(), FRAC_PI_2) * start.orientation;
    assert!(
        check_motion_after(turned, start, 49) > 0,
        "nothing lay behind"
    );
}

#[test]
fn debug_views_show_gbuffer_channels() {
    use lucid_passes::debug::debug_view::{self, View};
    let ctx = context(false);
    let mut renderer =
        Renderer::new(&ctx, scene("cornell-box"), SIZE, SIZE, Settings::default()).unwrap();
    let mut g = RenderGraph::new();
    let (images, _) = renderer.add_frame(&mut g);
    let views: Vec<_> = View::ALL
        .iter()
        .map(|&v| {
            let shown = debug_view::add_debug_view(&mut g, &images, v, SIZE, SIZE);
            (v, g.readback(shown))
        })
        .collect();
    let out = run(renderer.executor_mut(), g);
    for (view, id) in views {
        let image = out.image(id).unwrap();
        assert!(!image.has_non_finite(), "{view:?}");
        // Bottom centre of the Cornell box is the floor: normal +y, near-ish, white albedo.
        let floor = image.get(SIZE / 2, SIZE - 2).unwrap();
        match view {
            View::Normal => assert!(
                floor[1] > 0.95 && (floor[0] - 0.5).abs() < 0.05,
                "{floor:?}"
            ),
            View::Depth => assert!(floor[0] > 0.0 && floor[0] < 1.0, "{floor:?}"),
            View::Motion => assert!((floor[0] - 0.5).abs() < 1e-3, "still camera: {floor:?}"),
            View::Albedo => assert!(floor[0] > 0.5, "white floor: {floor:?}"),
            View::Gradient => assert_eq!(floor[..3], [0.0; 3], "no temporal SVGF, no rejection"),
            View::Final | View::Noisy => {}
        }
    }
    drop(renderer);
    assert_no_validation_messages(&ctx);
}
