//! Moving an instance: the first move rebuilds the scene on the GPU; later moves only write the
//! top level (TLAS, instances, lights), in place, from the next frame's graph. Both must give the
//! image a scene built with the object there gives.

use glam::{Affine3A, Vec3};
use lucid_passes::renderer::{Renderer, Settings};
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context};

/// The first frame of the Cornell box with its tall box moved through `offsets` in turn.
fn first_frame_after_moves(offsets: &[Vec3]) -> Vec<[f32; 4]> {
    let ctx = context(false);
    let scene = scene("cornell-box");
    let tall_box = scene.instances.len() - 1;
    let home = scene.instances[tall_box].transform;
    let mut r = Renderer::new(&ctx, scene, 24, 24, Settings::default()).expect("renderer");
    for &offset in offsets {
        r.set_instance_transform(tall_box, Affine3A::from_translation(offset) * home)
            .expect("move");
    }
    let image = r.render_and_read().expect("frame");
    drop(r);
    assert_no_validation_messages(&ctx);
    image.pixels
}

#[test]
fn a_second_move_written_in_place_matches_a_scene_rebuilt_there() {
    let here = Vec3::new(0.1, 0.0, 0.0);
    let there = Vec3::new(-0.2, 0.0, 0.1);
    let rebuilt = first_frame_after_moves(&[there]);
    let in_place = first_frame_after_moves(&[here, there]);
    assert_eq!(
        in_place, rebuilt,
        "the in-place top-level update must place the box"
    );
    let first_place = first_frame_after_moves(&[here]);
    assert_ne!(
        first_place, rebuilt,
        "the second move must change the image"
    );
}
