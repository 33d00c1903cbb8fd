//! The split view's picture: columns of one HDR image beside columns of another, copied into a new
//! image.

use ash::vk;
use lucid_engine::graph::{Access, ImageHandle, PassContext, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_present::image_copy;
use std::ops::Range;

/// The format of the composed image and of its inputs (that of the renderer's outputs).
pub const FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;

/// The first column of the right half of an image `width` pixels wide.
pub fn split_column(width: u32) -> u32 {
    width / 2
}

/// Adds the pass that shows `left` (a renderer's output) in columns `0..split_column(width)` and
/// `right` (an imported image written by an earlier submission) in the others; both inputs and the
/// returned image are `extent` in size.
pub fn add(
    graph: &mut RenderGraph,
    left: ImageHandle,
    right: ImageHandle,
    extent: [u32; 2],
) -> ImageHandle {
    let [width, height] = extent;
    let split = split_column(width);
    let mut p = graph.add_pass("sandbox.side_by_side");
    let left = p.read(left, Access::TransferRead);
    let right = p.read(right, Access::TransferRead);
    let out = p.create_image(
        "sandbox.side_by_side",
        ImageDesc::new(width, height, FORMAT),
    );
    let out = p.write(out, Access::TransferWrite);
    p.execute(move |pcx| {
        copy_columns(pcx, left, out, 0..split, height)?;
        copy_columns(pcx, right, out, split..width, height)
    });
    out
}

/// Records a copy of `columns` (all `height` rows) from `src` to the same place in `dst`, which a
/// pass declared as `TransferRead` and `TransferWrite`; both must be [`FORMAT`] images.
pub fn copy_columns(
    pcx: &PassContext<'_>,
    src: ImageHandle,
    dst: ImageHandle,
    columns: Range<u32>,
    height: u32,
) -> lucid_engine::Result<()> {
    if columns.is_empty() || height == 0 {
        return Ok(());
    }
    let (from, to) = (pcx.image(src)?, pcx.image(dst)?);
    let layers = image_copy::COLOR_LAYER;
    for image in [from, to] {
        let desc = image.desc();
        if desc.width < columns.end || desc.height < height || desc.format != FORMAT {
            return Err(lucid_engine::EngineError::InvalidArgument(format!(
                "the split view copies columns {columns:?} of {height} rows between {FORMAT:?} \
                 images; {} is {}x{} {:?}",
                image.name(),
                desc.width,
                desc.height,
                desc.format
            )));
        }
    }
    let region = vk::ImageCopy::default()
        .src_subresource(layers)
        .src_offset(vk::Offset3D {
            x: columns.start as i32,
            y: 0,
            z: 0,
        })
        .dst_subresource(layers)
        .dst_offset(vk::Offset3D {
            x: columns.start as i32,
            y: 0,
            z: 0,
        })
        .extent(vk::Extent3D {
            width: columns.end - columns.start,
            height,
            depth: 1,
        });
    image_copy::record(pcx, from, to, region);
    Ok(())
}
