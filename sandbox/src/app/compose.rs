//! The end of every frame's render graph: tone-map the frame source's output and copy it into the
//! swapchain image (or clear it when there is no output), draw the UI over it, optionally read
//! back the HDR output and the final image, and leave the image ready to present.

use super::gpu::{image_copy, PresentTarget};
use super::overlay::{Overlay, OverlayFrame};
use super::settings::DisplaySettings;
use super::tonemap;
use ash::vk;
use lucid_engine::graph::{Access, ImageHandle, ReadbackId, RenderGraph};
use lucid_engine::memory::{color_range, ResourceState};

/// Colour of the window where there is no frame to show.
const EMPTY: [f32; 4] = [0.05, 0.05, 0.06, 1.0];

/// What to add beyond showing the frame.
#[derive(Clone, Copy, Debug, Default)]
pub struct Extras {
    /// Read back the HDR output (an F12 capture).
    pub capture_hdr: bool,
    /// Read back the final image, UI included (`--screenshot-after`).
    pub screenshot: bool,
}

/// The readbacks a frame carries.
#[derive(Clone, Copy, Debug, Default)]
pub struct Readbacks {
    /// The HDR output.
    pub hdr: Option<ReadbackId>,
    /// The final swapchain image.
    pub screen: Option<ReadbackId>,
}

/// The stage at which a frame waits for its swapchain image: that of its first access.
pub fn acquire_wait_stage() -> vk::PipelineStageFlags2 {
    Access::TransferWrite.info().stage
}

/// Adds the passes that put `hdr` (or an empty background) and the UI (if any) on `target` and end
/// it in the present layout.
pub fn add(
    graph: &mut RenderGraph,
    hdr: Option<ImageHandle>,
    target: &PresentTarget,
    ui: Option<(&Overlay, OverlayFrame)>,
    display: &DisplaySettings,
    extras: Extras,
) -> anyhow::Result<Readbacks> {
    // The acquire semaphore is waited on at this stage, and the contents are discarded.
    target.image().set_tracked_state(ResourceState {
        layout: vk::ImageLayout::UNDEFINED,
        stage: acquire_wait_stage(),
        access: vk::AccessFlags2::NONE,
    });
    let desc = target.image().desc();
    let swap = graph.import_image("swapchain", target.image().clone());
    let mut readbacks = Readbacks::default();
    let swap = match hdr {
        Some(hdr) => {
            let bgra = desc.format == vk::Format::B8G8R8A8_UNORM;
            let ldr = tonemap::add(graph, hdr, [desc.width, desc.height], display, bgra);
            if extras.capture_hdr {
                readbacks.hdr = Some(graph.readback(hdr));
            }
            copy(graph, ldr, swap)
        }
        None => clear(graph, swap),
    };
    let swap = match ui {
        Some((overlay, frame)) => overlay.add_pass(graph, swap, target.index(), frame)?,
        None => swap,
    };
    if extras.screenshot {
        readbacks.screen = Some(graph.readback(swap));
    }
    let mut p = graph.add_pass("sandbox.present");
    p.read(swap, Access::Present);
    p.side_effect();
    p.execute(|_| Ok(()));
    Ok(readbacks)
}

fn copy(graph: &mut RenderGraph, src: ImageHandle, dst: ImageHandle) -> ImageHandle {
    let mut p = graph.add_pass("sandbox.copy_to_window");
    let src = p.read(src, Access::TransferRead);
    let dst = p.write(dst, Access::TransferWrite);
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

fn clear(graph: &mut RenderGraph, target: ImageHandle) -> ImageHandle {
    let mut p = graph.add_pass("sandbox.clear_window");
    let target = p.write(target, Access::TransferWrite);
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
