//! The display transform as a graph pass: the renderer's tone mapping (`lucid_passes::post::tonemap`),
//! with the bytes in the order of the image they are copied into.

use crate::settings::DisplaySettings;
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_passes::post::tonemap::{self, ChannelOrder};

/// Adds the tone-mapping pass reading `hdr`; returns an RGBA8 image of `extent` whose bytes are
/// in BGRA order when `bgra` is set.
pub fn add(
    graph: &mut RenderGraph,
    hdr: ImageHandle,
    extent: [u32; 2],
    display: &DisplaySettings,
    bgra: bool,
) -> ImageHandle {
    let order = if bgra {
        ChannelOrder::Bgra
    } else {
        ChannelOrder::Rgba
    };
    tonemap::add_tonemap_ordered(
        graph,
        hdr,
        extent[0],
        extent[1],
        display.png_encoding(),
        order,
    )
}
