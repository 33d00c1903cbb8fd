//! Tone mapping: exposure, a filmic curve (ACES fit or AgX) and sRGB, into an 8-bit image
//! (`shaders/tonemap/tonemap.comp`, identical to `lucid_engine::capture::PngEncoding`).
//!
//! The GPU side of the display transform, whose curves and CPU reference are owned by
//! `lucid_engine::capture` ([`PngEncoding`]). Headless renders use it in RGBA order; the window
//! (`lucid_present::PresentTarget`) uses it in the swapchain image's channel order.

use crate::shaders::tonemap::TONEMAP;
use lucid_engine::capture::{PngEncoding, ToneCurve};
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// The byte order of the 8-bit output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChannelOrder {
    /// Red first.
    Rgba,
    /// Blue first: bytes for copies into `B8G8R8A8` images (typical swapchains).
    Bgra,
}

/// Adds tone mapping of `hdr` (RGBA f32) with `encoding`; returns the sRGB-encoded RGBA8 image.
pub fn add_tonemap(
    g: &mut RenderGraph,
    hdr: ImageHandle,
    width: u32,
    height: u32,
    encoding: PngEncoding,
) -> ImageHandle {
    add_tonemap_ordered(g, hdr, width, height, encoding, ChannelOrder::Rgba)
}

/// Like [`add_tonemap`], with the channels stored in `order`.
pub fn add_tonemap_ordered(
    g: &mut RenderGraph,
    hdr: ImageHandle,
    width: u32,
    height: u32,
    encoding: PngEncoding,
    order: ChannelOrder,
) -> ImageHandle {
    let curve: u32 = match encoding.tone {
        ToneCurve::Clamp => 0,
        ToneCurve::Aces => 1,
        ToneCurve::AgX => 2,
    };
    let swap_rb = u32::from(order == ChannelOrder::Bgra);
    let mut pass = g.compute_pass("tonemap", &TONEMAP);
    pass.read("u_hdr", hdr);
    let ldr = pass.create_image("u_ldr", "tonemap.ldr", ImageDesc::rgba8(width, height));
    pass.push(&[encoding.exposure.to_bits(), curve, swap_rb]);
    pass.dispatch([width, height, 1]);
    ldr
}
