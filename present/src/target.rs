//! The swapchain image a frame draws on, and the passes that put a frame on it: the display
//! transform (`lucid_passes::tonemap` with the bytes in the image's channel order) copied into it,
//! or a clear where there is no frame, and the hand-over to presentation.

use crate::image_copy;
use ash::vk;
use lucid_engine::capture::PngEncoding;
use lucid_engine::graph::{Access, ImageHandle, RenderGraph};
use lucid_engine::memory::ResourceState;
use lucid_engine::memory::{color_range, Image};
use lucid_passes::post::tonemap::{self, ChannelOrder};
use std::sync::Arc;

/// Colour of the window where there is no frame to show.
const EMPTY: [f32; 4] = [0.05, 0.05, 0.06, 1.0];

/// The stage at which a frame waits for its swapchain image: that of its first access (the copy
/// or clear, a transfer write).
pub(crate) fn acquire_wait_stage() -> vk::PipelineStageFlags2 {
    Access::TransferWrite.info().stage
}

/// The swapchain image a frame draws on, from [`crate::Presenter::begin`].
///
/// [`Self::add_display`] adds everything a frame needs to show an HDR image. An application with
/// more to draw (e.g. a UI over the frame) adds the steps itself: [`Self::import`], then
/// [`Self::add_tone_map`] and [`Self::add_copy`] (or [`Self::add_clear`]), its own passes on the
/// image, and [`Self::add_present`] last.
///
/// ```no_run
/// # fn draw(target: lucid_present::PresentTarget, presenter: &mut lucid_present::Presenter, executor: &mut lucid_engine::graph::Executor, hdr_pass: impl FnOnce(&mut lucid_engine::graph::RenderGraph, [u32; 2]) -> lucid_engine::graph::ImageHandle) -> anyhow::Result<()> {
/// use lucid_engine::capture::{PngEncoding, ToneCurve};
/// let mut graph = lucid_engine::graph::RenderGraph::new();
/// let hdr = hdr_pass(&mut graph, target.extent()); // any float image of the target's size
/// let encoding = PngEncoding { exposure: 0.0, tone: ToneCurve::Aces };
/// target.add_display(&mut graph, hdr, encoding);
/// presenter.submit(executor, target, graph.compile()?, ())?;
/// # Ok(()) }
/// ```
pub struct PresentTarget {
    index: u32,
    image: Arc<Image>,
}

impl PresentTarget {
    /// Swapchain image `index`.
    pub(crate) fn new(index: u32, image: Arc<Image>) -> Self {
        Self { index, image }
    }

    /// The image's size in pixels (the size to render at).
    pub fn extent(&self) -> [u32; 2] {
        let desc = self.image.desc();
        [desc.width, desc.height]
    }

    /// Its index in the swapchain (e.g. to pick what was made per image of
    /// [`crate::Presenter::swapchain`], like framebuffers).
    pub fn index(&self) -> u32 {
        self.index
    }

    /// Adds the passes that tone-map `hdr` (an RGBA float image of [`Self::extent`], read as
    /// `Access::ComputeRead`) with `encoding` into the image and leave it ready to present.
    pub fn add_display(&self, graph: &mut RenderGraph, hdr: ImageHandle, encoding: PngEncoding) {
        let window = self.import(graph);
        let ldr = self.add_tone_map(graph, hdr, encoding);
        let window = self.add_copy(graph, ldr, window);
        self.add_present(graph, window);
    }

    /// Imports the image into `graph`, its contents discarded. Its first access must be a transfer
    /// write ([`Self::add_copy`] or [`Self::add_clear`]): the frame waits for the image there.
    pub fn import(&self, graph: &mut RenderGraph) -> ImageHandle {
        self.image.set_tracked_state(ResourceState {
            layout: vk::ImageLayout::UNDEFINED,
            stage: acquire_wait_stage(),
            access: vk::AccessFlags2::NONE,
        });
        graph.import_image("swapchain", self.image.clone())
    }

    /// Adds the tone mapping of `hdr` (an RGBA float image of [`Self::extent`]) with `encoding`;
    /// returns an 8-bit image of that size with its bytes in the order of the swapchain image's
    /// format, ready for [`Self::add_copy`].
    pub fn add_tone_map(
        &self,
        graph: &mut RenderGraph,
        hdr: ImageHandle,
        encoding: PngEncoding,
    ) -> ImageHandle {
        let order = if self.image.desc().format == vk::Format::B8G8R8A8_UNORM {
            ChannelOrder::Bgra
        } else {
            ChannelOrder::Rgba
        };
        let [width, height] = self.extent();
        tonemap::add_tonemap_ordered(graph, hdr, width, height, encoding, order)
    }

    /// Adds the copy of `ldr` (from [`Self::add_tone_map`]) into `window` (from [`Self::import`]);
    /// returns the written image.
    pub fn add_copy(
        &self,
        graph: &mut RenderGraph,
        ldr: ImageHandle,
        window: ImageHandle,
    ) -> ImageHandle {
        let mut p = graph.add_pass("present.copy_to_window");
        let src = p.read(ldr, Access::TransferRead);
        let dst = p.write(window, Access::TransferWrite);
        p.execute(move |pcx| {
            let (from, to) = (pcx.image(src)?, pcx.image(dst)?);
            let region = vk::ImageCopy::default()
                .src_subresource(image_copy::COLOR_LAYER)
                .dst_subresource(image_copy::COLOR_LAYER)
                .extent(to.desc().extent());
            // The window image and the tone-mapped output have the same size and texel size.
            image_copy::record(pcx, from, to, region);
            Ok(())
        });
        dst
    }

    /// Adds a clear of `window` (from [`Self::import`]) to a dark grey, for frames with nothing to
    /// show; returns the written image.
    pub fn add_clear(&self, graph: &mut RenderGraph, window: ImageHandle) -> ImageHandle {
        let mut p = graph.add_pass("present.clear_window");
        let target = p.write(window, Access::TransferWrite);
        p.execute(move |pcx| {
            let image = pcx.image(target)?;
            // SAFETY: cmd is recording; the graph put the image in TRANSFER_DST_OPTIMAL.
            unsafe {
                pcx.context().device().cmd_clear_color_image(
                    pcx.command_buffer(),
                    image.raw(),
                    vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                    &vk::ClearColorValue { float32: EMPTY },
                    &[color_range()],
                )
            };
            Ok(())
        });
        target
    }

    /// Adds the last pass on `window`, which leaves it in the present layout.
    pub fn add_present(&self, graph: &mut RenderGraph, window: ImageHandle) {
        let mut p = graph.add_pass("present.to_window");
        p.read(window, Access::Present);
        p.side_effect();
        p.execute(|_| Ok(()));
    }
}
