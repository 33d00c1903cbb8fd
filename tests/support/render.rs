//! Rendering helpers for frame-capture tests.

use lucid_engine::capture::ImageData;
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::scene::{builtin, Scene};
use lucid_engine::Context;
use lucid_passes::renderer::{Algorithm, FrameImages, Renderer, SamplesPerPixel, Settings};

/// Builds a built-in scene, panicking with the error if it cannot.
pub fn scene(name: &str) -> Scene {
    builtin::build(name).unwrap_or_else(|e| panic!("built-in scene {name}: {e}"))
}

/// Renders `frames` accumulated frames of `scene` at `size` with `settings` and returns the
/// accumulated HDR image, checking that no validation message was produced.
pub fn render_accumulated(
    scene: Scene,
    size: (u32, u32),
    settings: Settings,
    frames: u32,
) -> ImageData {
    render_accumulated_on(&crate::context(false), scene, size, settings, frames)
}

/// [`render_accumulated`] on `ctx` (a validated context): tests that render many images share
/// one (an H100's driver refused new instances after a few dozen in one process; that was before
/// the engine kept the drivers loaded between contexts, `engine/src/context/driver_residency.rs`,
/// and has not been tried since).
pub fn render_accumulated_on(
    ctx: &Context,
    scene: Scene,
    size: (u32, u32),
    settings: Settings,
    frames: u32,
) -> ImageData {
    let mut renderer = Renderer::new(
        ctx,
        scene,
        size.0,
        size.1,
        Settings {
            accumulate: true,
            ..settings
        },
    )
    .expect("renderer");
    for _ in 1..frames {
        renderer.render().expect("frame");
    }
    let image = renderer.render_and_read().expect("last frame");
    assert_eq!(renderer.stats().non_finite_samples, 0, "no NaN/Inf samples");
    drop(renderer);
    crate::assert_no_validation_messages(ctx);
    image
}

/// Renders the renderer's next frame and reads back the images `pick` chooses of it.
pub fn frame_images<const N: usize>(
    renderer: &mut Renderer,
    pick: impl FnOnce(&FrameImages) -> [ImageHandle; N],
) -> [ImageData; N] {
    let mut g = RenderGraph::new();
    let (images, _) = renderer.add_frame(&mut g);
    let ids = pick(&images).map(|image| g.readback(image));
    let outputs = crate::run(renderer.executor_mut(), g);
    ids.map(|id| outputs.image(id).expect("read-back image"))
}

/// One frame of `spp` samples per pixel of `scene` at `size` x `size` with `algorithm` and
/// `max_depth` (other settings default); the HDR image.
pub fn render_once(
    scene: Scene,
    algorithm: Algorithm,
    spp: u32,
    max_depth: u32,
    size: u32,
) -> ImageData {
    let settings = Settings {
        algorithm,
        samples_per_pixel: SamplesPerPixel::new(spp).expect("at least one sample"),
        max_depth,
        ..Settings::default()
    };
    render_accumulated(scene, (size, size), settings, 1)
}

/// The G-buffer of one frame of `scene` at `size` x `size` (default settings): its albedo and its
/// normal-and-roughness images.
pub fn gbuffer_once(scene: Scene, size: u32) -> [ImageData; 2] {
    let ctx = crate::context(false);
    let mut renderer =
        Renderer::new(&ctx, scene, size, size, Settings::default()).expect("renderer");
    let images = frame_images(&mut renderer, |i| {
        [i.gbuffer.albedo, i.gbuffer.normal_roughness]
    });
    drop(renderer);
    crate::assert_no_validation_messages(&ctx);
    images
}

/// The mean of channel `c` over `pixels` (column, row) of `image`.
pub fn mean_at(image: &ImageData, pixels: &[(u32, u32)], c: usize) -> f32 {
    let sum: f32 = pixels
        .iter()
        .map(|&(x, y)| image.get(x, y).expect("pixel in the image")[c])
        .sum();
    sum / pixels.len() as f32
}
