//! The renderer's automatic BVH layout: the wide one for path tracing a scene walked in workgroup
//! memory (the Cornell box), the binary one for BDPT and for larger scenes; a layout asked for
//! stays until the automatic choice is asked for again; both layouts render the same image.

use lucid_engine::scene::builtin::{self, BuildOptions};
use lucid_engine::scene::gpu::BvhLayout;
use lucid_passes::renderer::{automatic_layout, Algorithm, Renderer, Settings};
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context};

fn settings(algorithm: Algorithm) -> Settings {
    Settings {
        algorithm,
        ..Settings::default()
    }
}

#[test]
fn path_tracing_a_small_scene_takes_the_wide_layout_and_bdpt_the_binary_one() {
    let ctx = context(false);
    let pt = settings(Algorithm::PathTracing);
    let bdpt = settings(Algorithm::Bidirectional);
    let mut r = Renderer::new(&ctx, scene("cornell-box"), 16, 16, pt).expect("renderer");
    assert_eq!(r.bvh_layout(), BvhLayout::Wide);
    let wide = r.render_and_read().expect("frame").pixels;
    let mut binary = Renderer::new(&ctx, scene("cornell-box"), 16, 16, pt).expect("renderer");
    binary
        .set_bvh_layout(Some(BvhLayout::Binary))
        .expect("layout");
    let binary = binary.render_and_read().expect("frame").pixels;
    let differing = wide.iter().zip(&binary).filter(|(a, b)| a != b).count();
    assert!(
        differing * 50 <= wide.len(),
        "{differing} of {} pixels differ between the layouts",
        wide.len()
    );
    r.set_settings(bdpt).expect("settings");
    assert_eq!(r.bvh_layout(), BvhLayout::Binary);
    r.set_settings(pt).expect("settings");
    assert_eq!(r.bvh_layout(), BvhLayout::Wide);
    r.set_bvh_layout(Some(BvhLayout::Binary)).expect("layout");
    r.set_settings(bdpt).expect("settings");
    r.set_settings(pt).expect("settings");
    assert_eq!(
        r.bvh_layout(),
        BvhLayout::Binary,
        "a layout asked for stays"
    );
    r.set_bvh_layout(None).expect("layout");
    assert_eq!(
        r.bvh_layout(),
        BvhLayout::Wide,
        "back to the automatic choice"
    );
    drop(r);
    assert_no_validation_messages(&ctx);
}

#[test]
fn larger_scenes_keep_the_binary_layout() {
    let ctx = context(false);
    let options = BuildOptions { detail: 0.02 };
    let teapot = builtin::build_with("cornell-teapot", &options).unwrap();
    let r =
        Renderer::new(&ctx, teapot, 16, 16, settings(Algorithm::PathTracing)).expect("renderer");
    assert_eq!(r.bvh_layout(), BvhLayout::Binary);
    assert_eq!(
        automatic_layout(Algorithm::PathTracingWavefront, r.gpu_scene()),
        BvhLayout::Binary,
        "the wavefront's kernels read the buffers"
    );
    drop(r);
    assert_no_validation_messages(&ctx);
}
