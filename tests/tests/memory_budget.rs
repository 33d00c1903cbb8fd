//! Device memory through the embedding API: a scene or a frame that does not fit in the memory
//! budget (`ContextDesc::memory_budget_mib`, else the device-local heap) is an error naming what
//! does not fit, returned before Vulkan is asked; the renderer stays usable at a size that fits.

use glam::{UVec3, Vec3};
use lucid_engine::scene::Mesh;
use lucid_engine::{Context, ContextDesc, EngineError};
use lucid_passes::renderer::{Renderer, Settings};
use lucid_tests::assert_no_validation_messages;
use lucid_tests::render::scene;

fn context_with_budget(mib: u64) -> Context {
    let desc = ContextDesc {
        memory_budget_mib: Some(mib),
        ..ContextDesc::for_tests(false)
    };
    Context::new(&desc).expect("create a Vulkan context")
}

fn assert_does_not_fit(result: Result<(), EngineError>, what: &str) -> String {
    match result {
        Err(e @ EngineError::DoesNotFit { .. }) => e.to_string(),
        other => panic!("{what}: expected an out-of-memory error, got {other:?}"),
    }
}

/// A flat `n` x `n` grid of quads (2 n² triangles).
fn grid(n: u32) -> Mesh {
    let positions: Vec<Vec3> = (0..=n)
        .flat_map(|y| {
            (0..=n).map(move |x| Vec3::new(x as f32 / n as f32, y as f32 / n as f32, -1.5))
        })
        .collect();
    let at = |x: u32, y: u32| y * (n + 1) + x;
    let indices = (0..n)
        .flat_map(|y| (0..n).map(move |x| (x, y)))
        .flat_map(|(x, y)| {
            [
                UVec3::new(at(x, y), at(x + 1, y), at(x + 1, y + 1)),
                UVec3::new(at(x, y), at(x + 1, y + 1), at(x, y + 1)),
            ]
        })
        .collect();
    Mesh {
        name: "grid".into(),
        normals: vec![Vec3::Z; positions.len()],
        positions,
        indices,
        ..Mesh::default()
    }
}

/// Renders the Cornell box with a 180 000-triangle grid under a budget of `mib`: the error's
/// message, after checking that it says the budget and that nothing stays allocated.
fn refuse_big_scene(mib: u64) -> String {
    let ctx = context_with_budget(mib);
    let mut big = scene("cornell-box");
    big.add_mesh_instance(grid(300));
    let message = assert_does_not_fit(
        Renderer::new(&ctx, big, 16, 16, Settings::default()).map(drop),
        &format!("180 000 triangles in {mib} MiB"),
    );
    assert!(
        message.contains(&format!("LUCID_MEMORY_BUDGET_MIB={mib}")),
        "{message}"
    );
    assert_eq!(
        ctx.memory_report().allocated_bytes,
        0,
        "nothing is left allocated"
    );
    assert_no_validation_messages(&ctx);
    message
}

#[test]
fn a_scene_whose_geometry_cannot_fit_is_refused_before_its_bvh_is_built() {
    // 180 000 triangles need at least 10 MiB (indices, triangle records, vertices).
    let message = refuse_big_scene(8);
    assert!(
        message.contains("for the geometry of scene") && message.contains("triangles, at least"),
        "names the scene and says it is a lower bound: {message}"
    );
}

#[test]
fn a_scene_beyond_the_budget_is_refused_naming_its_buffer() {
    // The geometry alone (10 MiB) fits in 12 MiB; with its BVH the scene does not.
    let message = refuse_big_scene(12);
    assert!(
        message.contains(" MiB for b_"),
        "names the scene buffer: {message}"
    );
}

#[test]
fn a_frame_beyond_the_budget_is_refused_and_a_smaller_one_renders() {
    let ctx = context_with_budget(16);
    let mut renderer = Renderer::new(&ctx, scene("cornell-box"), 1024, 1024, Settings::default())
        .expect("renderer");
    let message = assert_does_not_fit(renderer.render().map(drop), "a 1024x1024 frame in 16 MiB");
    assert!(message.contains("for the frame's"), "{message}");
    assert!(
        message.contains("path_trace"),
        "names the largest image: {message}"
    );
    renderer.resize(32, 32).expect("resize");
    let image = renderer.render_and_read().expect("a 32x32 frame fits");
    assert_eq!((image.width, image.height), (32, 32));
    drop(renderer);
    assert_no_validation_messages(&ctx);
}
