//! The light transport's frames (every algorithm: path tracing, BDPT, the wavefront path tracers) are a pure function of (scene, camera, settings, frame index, seed):
//! rendering the same frame again gives the same image bit for bit and the same ray count; another
//! seed gives another image. The images for a denoiser are traced only when one runs, and tracing
//! them leaves the radiance unchanged.

use lucid_engine::capture::ImageData;
use lucid_passes::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_tests::render::{frame_images, scene};
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
    for algorithm in Algorithm::ALL {
        let base = Settings {
            algorithm,
            samples_per_pixel: SamplesPerPixel::new(2).unwrap(),
            accumulate: false,
            ..Settings::default()
        };
        repeats_bit_for_bit(&ctx, base);
    }
}

/// Renders `base` twice and with another seed.
fn repeats_bit_for_bit(ctx: &lucid_engine::Context, base: Settings) {
    let algorithm = base.algorithm;
    let (reference, rays) = render(ctx, base);
    let (again, rays_again) = render(ctx, base);
    let (other_seed, _) = render(ctx, Settings { seed: 7, ..base });
    assert_no_validation_messages(ctx);

    assert!(
        rays > SIZE.0 * SIZE.1 * 2,
        "{algorithm:?}: rays are counted ({rays})"
    );
    assert_eq!(
        differing(&reference, &again),
        0,
        "{algorithm:?}: the same frame renders the same bits"
    );
    assert_eq!(rays, rays_again);
    let differing = differing(&reference, &other_seed);
    assert!(
        differing > reference.pixels.len() / 2,
        "{algorithm:?}: another seed changes most pixels ({differing} of {})",
        reference.pixels.len()
    );
}

/// The second frame's noisy radiance, and whether the frame traced the demodulated image (and
/// the plan kept the G-buffer pass, which only a denoiser needs).
fn radiance(ctx: &lucid_engine::Context, settings: Settings) -> (ImageData, bool) {
    let mut r =
        Renderer::new(ctx, scene("cornell-box"), SIZE.0, SIZE.1, settings).expect("renderer");
    r.render().expect("frame 0");
    let gbuffer_kept = r.frame_plan().expect("plan").pass("gbuffer").is_some();
    let mut traced = false;
    let [radiance] = frame_images(&mut r, |images| {
        traced = images.demodulated.is_some();
        [images.radiance]
    });
    assert_eq!(
        gbuffer_kept, traced,
        "the G-buffer is culled exactly when no denoiser runs"
    );
    (radiance, traced)
}

#[test]
fn denoiser_images_are_traced_only_for_a_denoiser_and_leave_the_radiance_alone() {
    let ctx = context(false);
    for algorithm in Algorithm::ALL {
        let plain = Settings {
            algorithm,
            accumulate: false,
            ..Settings::default()
        };
        let (without, traced_without) = radiance(&ctx, plain);
        let (with, traced_with) = radiance(
            &ctx,
            Settings {
                denoiser: Denoiser::Svgf,
                ..plain
            },
        );
        assert!(!traced_without, "{algorithm:?}: traced for no denoiser");
        assert!(traced_with, "{algorithm:?}: not traced for SVGF");
        assert_eq!(
            differing(&without, &with),
            0,
            "{algorithm:?}: tracing the denoiser's images changed the radiance"
        );
    }
    assert_no_validation_messages(&ctx);
}
