//! The path tracer's frames are a pure function of (scene, camera, settings, frame index, seed):
//! rendering the same frame again gives the same image bit for bit and the same ray count; another
//! seed gives another image.

use lucid_engine::capture::ImageData;
use lucid_passes::renderer::{Renderer, Settings};
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context};

/// 44x36 leaves partial 8x8 tiles on the right and bottom edges.
const SIZE: (u32, u32) = (44, 36);

fn render(ctx: &lucid_engine::Context, settings: Settings) -> (ImageData, u32) {
    let mut r =
        Renderer::new(ctx, scene("cornell-box"), SIZE.0, SIZE.1, settings).expect("renderer");
    r.render().expect("frame 0");
    let image = r.render_and_read().expect("frame 1");
    (image, r.stats().rays)
}

/// Pixels whose bits differ.
fn differing(a: &ImageData, b: &ImageData) -> usize {
    assert_eq!((a.width, a.height), (b.width, b.height));
    a.pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| p.map(f32::to_bits) != q.map(f32::to_bits))
        .count()
}

#[test]
fn frames_repeat_bit_for_bit_and_depend_on_the_seed() {
    let ctx = context(false);
    let base = Settings {
        samples_per_pixel: 2,
        accumulate: false,
        ..Settings::default()
    };
    let (reference, rays) = render(&ctx, base);
    let (again, rays_again) = render(&ctx, base);
    let (other_seed, _) = render(&ctx, Settings { seed: 7, ..base });
    assert_no_validation_messages(&ctx);

    assert!(rays > SIZE.0 * SIZE.1 * 2, "rays are counted ({rays})");
    assert_eq!(
        differing(&reference, &again),
        0,
        "the same frame renders the same bits"
    );
    assert_eq!(rays, rays_again);
    let differing = differing(&reference, &other_seed);
    assert!(
        differing > reference.pixels.len() / 2,
        "another seed changes most pixels ({differing} of {})",
        reference.pixels.len()
    );
}
