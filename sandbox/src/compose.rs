//! The end of every frame's render graph: the window image (through `lucid_present`'s display
//! passes) showing the frame source's output tone-mapped (or empty when there is no output), the UI
//! over it, optionally read back the HDR output and the final image, and the image left ready to
//! present.

use super::overlay::{Overlay, OverlayFrame};
use super::settings::DisplaySettings;
use lucid_engine::graph::{ImageHandle, ReadbackId, RenderGraph};
use lucid_present::PresentTarget;

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
    let swap = target.import(graph);
    let mut readbacks = Readbacks::default();
    let swap = match hdr {
        Some(hdr) => {
            let ldr = target.add_tone_map(graph, hdr, display.png_encoding());
            if extras.capture_hdr {
                readbacks.hdr = Some(graph.readback(hdr));
            }
            target.add_copy(graph, ldr, swap)
        }
        None => target.add_clear(graph, swap),
    };
    let swap = match ui {
        Some((overlay, frame)) => overlay.add_pass(graph, swap, target.index(), frame)?,
        None => swap,
    };
    if extras.screenshot {
        readbacks.screen = Some(graph.readback(swap));
    }
    target.add_present(graph, swap);
    Ok(readbacks)
}
