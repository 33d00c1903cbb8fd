//! Zeroed images that stand in for an input a frame does not have: shaders bind by reflected name
//! and every binding must be bound, so a pass whose shader would not read the input this frame
//! binds one of these.

use lucid_engine::graph::{Access, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// Adds a pass creating the zeroed image `name` of `desc`.
pub fn add_zero_image(g: &mut RenderGraph, name: &str, desc: ImageDesc) -> ImageHandle {
    let mut p = g.add_pass(name);
    let image = p.create_image(name, desc);
    let image = p.write(image, Access::TransferWrite);
    p.execute(move |ctx| ctx.clear_image(image, [0.0; 4]));
    image
}
