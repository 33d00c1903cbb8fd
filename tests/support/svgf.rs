//! Shared by the denoiser tests (SVGF and the learned denoiser): one renderer per method, frames read back, luminance statistics over
//! pixel masks.

use crate::render::frame_images;
use lucid_engine::capture::{rec709_luminance, ImageData};
use lucid_engine::scene::{Camera, Material, Scene};
use lucid_engine::Context;
use lucid_passes::denoise::svgf::{SvgfMode, SvgfParams};
use lucid_passes::renderer::{Denoiser, Renderer, SamplesPerPixel, Settings};

/// Side of the square test images.
pub const SIZE: u32 = 64;

/// How a sequence is rendered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// 1 spp, no denoiser.
    Noisy,
    /// The a-trous filter alone on each 1-spp frame.
    PerFrame,
    /// Full SVGF at 1 spp.
    Svgf,
    /// SVGF at 1 spp without temporal gradients (history rejected by geometry only).
    SvgfWithoutGradients,
    /// The learned recurrent denoiser at 1 spp.
    Neural,
}

/// The settings of `method`, without accumulation, paths up to `max_depth`.
pub fn settings(method: Method, max_depth: u32) -> Settings {
    let svgf = |mode, gradients| SvgfParams {
        mode,
        gradients,
        ..SvgfParams::default()
    };
    let (denoiser, svgf) = match method {
        Method::Noisy => (Denoiser::None, SvgfParams::default()),
        Method::PerFrame => (Denoiser::Svgf, svgf(SvgfMode::EveryFrame, true)),
        Method::Svgf => (Denoiser::Svgf, svgf(SvgfMode::Temporal, true)),
        Method::SvgfWithoutGradients => (Denoiser::Svgf, svgf(SvgfMode::Temporal, false)),
        Method::Neural => (Denoiser::Neural, SvgfParams::default()),
    };
    Settings {
        samples_per_pixel: SamplesPerPixel::ONE,
        max_depth,
        accumulate: false,
        denoiser,
        svgf,
        ..Settings::default()
    }
}

/// `settings` with SVGF's firefly clamp on or off.
pub fn with_firefly_clamp(settings: Settings, firefly_clamp: bool) -> Settings {
    Settings {
        svgf: SvgfParams {
            firefly_clamp,
            ..settings.svgf
        },
        ..settings
    }
}

/// A renderer of `scene` with `settings`.
pub fn renderer(ctx: &Context, scene: Scene, settings: Settings) -> Renderer {
    Renderer::new(ctx, scene, SIZE, SIZE, settings).expect("renderer")
}

/// A reference image of `scene` seen by `camera`: `frames` accumulated frames of `spp` samples
/// (paths up to `max_depth`) by a fresh renderer. Every reference frame thus draws the same random
/// numbers per pixel, so that its residual noise changes little from frame to frame: a reference
/// that flickered would add its own flicker to every method's temporal instability.
pub fn reference(
    ctx: &Context,
    scene: &Scene,
    camera: Camera,
    (spp, frames): (u32, u32),
    max_depth: u32,
) -> ImageData {
    let settings = Settings {
        samples_per_pixel: SamplesPerPixel::new(spp).expect("at least one sample per pixel"),
        max_depth,
        accumulate: true,
        ..Settings::default()
    };
    let mut r = Renderer::new(ctx, scene.clone(), SIZE, SIZE, settings).expect("renderer");
    r.set_camera(camera);
    for _ in 1..frames {
        r.render().expect("frame");
    }
    frame(&mut r)
}

/// Renders a frame and reads its (denoised) HDR output back, checking it is finite.
pub fn frame(renderer: &mut Renderer) -> ImageData {
    let image = renderer.render_and_read().expect("frame");
    assert!(!image.has_non_finite(), "the output has NaN or Inf pixels");
    image
}

/// Mean luminance of `image` over the pixels where `mask` is true.
pub fn mean_luminance(image: &ImageData, mask: &[bool]) -> f64 {
    let (sum, count) = image
        .pixels
        .iter()
        .zip(mask)
        .filter(|(_, &m)| m)
        .fold((0.0, 0usize), |(s, c), (&p, _)| {
            (s + f64::from(rec709_luminance(p)), c + 1)
        });
    sum / count.max(1) as f64
}

/// Mean absolute luminance error of `test` against `reference` over `mask`, relative to the
/// reference's mean luminance there.
pub fn relative_error(test: &ImageData, reference: &ImageData, mask: &[bool]) -> f64 {
    let (sum, count) = test
        .pixels
        .iter()
        .zip(&reference.pixels)
        .zip(mask)
        .filter(|(_, &m)| m)
        .fold((0.0, 0usize), |(s, c), ((&t, &r), _)| {
            let d = f64::from(rec709_luminance(t) - rec709_luminance(r)).abs();
            (s + d, c + 1)
        });
    sum / count.max(1) as f64 / mean_luminance(reference, mask).max(1e-6)
}

/// A mask of every pixel.
pub fn everywhere() -> Vec<bool> {
    vec![true; (SIZE * SIZE) as usize]
}

/// The object id of every pixel of the next frame (the frame is rendered and discarded).
pub fn object_ids(r: &mut Renderer) -> Vec<f32> {
    let [ids] = frame_images(r, |images| [images.gbuffer.ids]);
    ids.pixels.iter().map(|p| p[0]).collect()
}

/// The Cornell box's light material index and the material with its emission switched off.
pub fn light_switched_off(cornell: &Scene) -> (usize, Material) {
    let light = cornell
        .materials
        .iter()
        .position(|m| m.name == "light")
        .expect("the Cornell box has a light material");
    let mut off = cornell.materials[light].clone();
    off.emission = glam::Vec3::ZERO;
    (light, off)
}
