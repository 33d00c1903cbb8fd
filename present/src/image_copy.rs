//! Recording an image-to-image copy inside a render-graph pass (the copy into the window image;
//! public for applications composing images in their own passes, e.g. the sandbox's split view).

use ash::vk;
use lucid_engine::graph::PassContext;
use lucid_engine::memory::Image;

/// The colour aspect of mip 0, layer 0: what these copies move.
pub const COLOR_LAYER: vk::ImageSubresourceLayers = vk::ImageSubresourceLayers {
    aspect_mask: vk::ImageAspectFlags::COLOR,
    mip_level: 0,
    base_array_layer: 0,
    layer_count: 1,
};

/// Records a copy of `region` from `from` to `to`. The pass must have declared them as
/// `TransferRead` and `TransferWrite` (so the graph put them in the transfer layouts), and the
/// caller has checked that the region lies in both and their texels have the same size.
pub fn record(pcx: &PassContext<'_>, from: &Image, to: &Image, region: vk::ImageCopy) {
    // SAFETY: cmd is recording; the layouts and the region are the caller's guarantees above.
    unsafe {
        pcx.context().device().cmd_copy_image(
            pcx.command_buffer(),
            from.raw(),
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            to.raw(),
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            &[region],
        )
    };
}
