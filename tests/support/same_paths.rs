//! Renders that draw the same random numbers and should give the same image: how two such images
//! differ, and one frame's images and ray count (the wavefront and long-path tests).

use crate::render::scene;
use lucid_engine::capture::ImageData;
use lucid_engine::graph::RenderGraph;
use lucid_engine::Context;
use lucid_passes::renderer::{Renderer, Settings};

/// How two renders with the same random numbers differ.
#[derive(Debug)]
pub struct Difference {
    /// Share of pixel channels whose relative difference is above 1e-3.
    pub differing: f64,
    /// The largest difference of the image's channel means relative to the channel's mean
    /// magnitude (its mean absolute value: gradient images are signed and their means near 0).
    pub mean: f64,
}

pub fn difference(a: &ImageData, b: &ImageData) -> Difference {
    let mut differing = 0usize;
    let mut sums = [[0.0f64; 3]; 2];
    let mut magnitudes = [0.0f64; 3];
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        for c in 0..3 {
            let (x, y) = (f64::from(p[c]), f64::from(q[c]));
            if (x - y).abs() > 1e-3 * (x.abs() + y.abs()).max(1e-6) {
                differing += 1;
            }
            sums[0][c] += x;
            sums[1][c] += y;
            magnitudes[c] += x.abs();
        }
    }
    Difference {
        differing: differing as f64 / (3 * a.pixels.len()) as f64,
        mean: (0..3)
            .map(|c| (sums[0][c] - sums[1][c]).abs() / magnitudes[c].max(1e-9))
            .fold(0.0, f64::max),
    }
}

/// One `size`x`size` frame of `name` with `settings` (SVGF: the surface images are written) on `ctx`: its
/// radiance and, with a denoiser, its demodulated radiance; and the rays traced.
pub fn one_frame(
    ctx: &Context,
    name: &str,
    size: u32,
    settings: Settings,
) -> (Vec<ImageData>, u32) {
    let mut renderer = Renderer::new(ctx, scene(name), size, size, settings).expect("renderer");
    let mut g = RenderGraph::new();
    let (images, stats) = renderer.add_frame(&mut g);
    let mut handles = vec![images.radiance];
    handles.extend(images.demodulated);
    let ids: Vec<_> = handles.into_iter().map(|h| g.readback(h)).collect();
    let outputs = crate::run(renderer.executor_mut(), g);
    let images = ids
        .into_iter()
        .map(|id| outputs.image(id).expect("read-back image"))
        .collect();
    let stats: &[u32] = bytemuck::cast_slice(outputs.bytes(stats).expect("stats"));
    assert_eq!(stats[0], 0, "no non-finite samples");
    drop(renderer);
    crate::assert_no_validation_messages(ctx);
    (images, stats[1])
}
