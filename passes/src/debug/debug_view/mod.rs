//! Debug views: any intermediate image of a frame mapped to displayable linear RGB
//! (`shaders/debug_view/debug_view.comp`).

use crate::plumbing::placeholder::add_zero_image;
use crate::renderer::FrameImages;
use crate::shaders::debug_view::DEBUG_VIEW;
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// What to show instead of the final image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// The final (accumulated, denoised) image.
    #[default]
    Final,
    /// This frame's noisy radiance.
    Noisy,
    /// The G-buffer's demodulation albedo.
    Albedo,
    /// World normals as colours.
    Normal,
    /// View depth, near = white.
    Depth,
    /// Motion vectors (x red, y green, 0.5 = still).
    Motion,
    /// The share of SVGF's history its temporal gradients drop (red; black where shading did not
    /// change, and everywhere without temporal SVGF).
    Gradient,
}

impl View {
    /// Every view, for menus.
    pub const ALL: [View; 7] = [
        View::Final,
        View::Noisy,
        View::Albedo,
        View::Normal,
        View::Depth,
        View::Motion,
        View::Gradient,
    ];

    /// The name in menus.
    pub fn label(self) -> &'static str {
        match self {
            View::Final => "final image",
            View::Noisy => "noisy radiance",
            View::Albedo => "albedo",
            View::Normal => "normal",
            View::Depth => "depth",
            View::Motion => "motion",
            View::Gradient => "history rejection",
        }
    }
}

/// The image `view` shows of `frame` (a visualisation pass for G-buffer channels).
pub fn add_debug_view(
    g: &mut RenderGraph,
    frame: &FrameImages,
    view: View,
    width: u32,
    height: u32,
) -> ImageHandle {
    let (source, mode) = match view {
        View::Final => return frame.hdr,
        View::Noisy => return frame.radiance,
        View::Albedo => (frame.gbuffer.albedo, 0u32),
        View::Normal => (frame.gbuffer.normal_roughness, 1),
        View::Depth => (frame.gbuffer.depth, 2),
        View::Motion => (frame.gbuffer.motion, 3),
        View::Gradient => match frame.gradient {
            Some(gradient) => (gradient, 4),
            // Without temporal SVGF nothing is rejected: black.
            None => (
                add_zero_image(g, "debug_view.no_gradient", ImageDesc::rgba32f(1, 1)),
                4,
            ),
        },
    };
    let mut pass = g.compute_pass("debug_view", &DEBUG_VIEW);
    pass.sample("u_source", source);
    let out = pass.create_image("u_out", "debug_view.out", ImageDesc::rgba32f(width, height));
    pass.push(&[mode, 10.0f32.to_bits()]);
    pass.dispatch([width, height, 1]);
    out
}
