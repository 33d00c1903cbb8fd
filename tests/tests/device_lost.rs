//! Device loss through the embedding API: a frame whose submission reports `VK_ERROR_DEVICE_LOST`
//! (injected with `ContextDesc::inject_device_lost_at_frame`) makes `Renderer::render` return a
//! clear error naming the frame and its passes; every later call fails the same way, without a
//! panic or a hang, and dropping the renderer and the context is clean. So does a loss that
//! presenting reports (`Context::observe`).

use lucid_engine::error::from_vk;
use lucid_engine::{Context, ContextDesc, EngineError};
use lucid_passes::renderer::{Renderer, Settings};
use lucid_tests::assert_no_validation_messages;
use lucid_tests::render::scene;

fn context_losing_frame(frame: u64) -> Context {
    let desc = ContextDesc {
        inject_device_lost_at_frame: Some(frame),
        ..ContextDesc::for_tests(false)
    };
    Context::new(&desc).expect("create a Vulkan context")
}

fn assert_device_lost(result: Result<impl std::fmt::Debug, EngineError>, what: &str) -> String {
    match result {
        Err(e @ EngineError::DeviceLost { .. }) => e.to_string(),
        other => panic!("{what}: expected a device loss, got {other:?}"),
    }
}

#[test]
fn a_lost_device_fails_this_and_every_later_frame_with_a_clear_error() {
    let ctx = context_losing_frame(3);
    let mut renderer =
        Renderer::new(&ctx, scene("cornell-box"), 16, 16, Settings::default()).expect("renderer");
    renderer.render().expect("frame 1 runs");
    renderer.render().expect("frame 2 runs");
    let message = assert_device_lost(renderer.render(), "frame 3");
    assert!(message.contains("the GPU device was lost"), "{message}");
    assert!(message.contains("frame 3"), "{message}");
    assert!(
        message.contains("path_trace"),
        "names the passes: {message}"
    );
    assert!(message.contains("LUCID_INJECT_DEVICE_LOST"), "{message}");
    assert!(!message.contains('\n'), "one line: {message}");
    assert!(ctx.is_device_lost());

    assert_device_lost(renderer.render(), "a frame after the loss");
    assert_device_lost(renderer.render_and_read(), "a read frame after the loss");
    assert_device_lost(renderer.finish(), "waiting after the loss");
    assert_device_lost(
        Renderer::new(&ctx, scene("cornell-box"), 16, 16, Settings::default()).map(drop),
        "a new renderer on the lost device (its scene upload)",
    );
    drop(renderer);
    assert_no_validation_messages(&ctx);
}

#[test]
fn a_read_frame_that_loses_the_device_returns_the_error() {
    let ctx = context_losing_frame(1);
    let mut renderer =
        Renderer::new(&ctx, scene("cornell-box"), 16, 16, Settings::default()).expect("renderer");
    let message = assert_device_lost(renderer.render_and_read(), "frame 1");
    assert!(message.contains("frame 1"), "{message}");
    drop(renderer);
    assert_no_validation_messages(&ctx);
}

/// A loss reported by a call outside the engine on its device (presenting to a window, as
/// `lucid_present` does) makes every later frame fail the same way.
#[test]
fn a_loss_reported_while_presenting_fails_every_later_frame() {
    let ctx = Context::new(&ContextDesc::for_tests(false)).expect("create a Vulkan context");
    let mut renderer =
        Renderer::new(&ctx, scene("cornell-box"), 16, 16, Settings::default()).expect("renderer");
    renderer.render().expect("frame 1 runs");
    let reported = ctx.observe(from_vk(
        "vkQueuePresentKHR",
        ash::vk::Result::ERROR_DEVICE_LOST,
    ));
    let message = assert_device_lost(Err::<(), _>(reported), "the present");
    assert!(message.contains("vkQueuePresentKHR"), "{message}");
    assert!(ctx.is_device_lost());
    assert_device_lost(renderer.render(), "the frame after the present");
    drop(renderer);
    assert_no_validation_messages(&ctx);
}
