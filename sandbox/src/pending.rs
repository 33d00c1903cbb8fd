//! What a submitted frame still has to deliver once the GPU finishes it: an F12 capture and the
//! `--screenshot-after` image.

use super::capture;
use super::compose::Readbacks;
use super::settings::DisplaySettings;
use lucid_engine::graph::FrameOutputs;
use std::path::{Path, PathBuf};

/// An F12 capture in flight.
#[derive(Clone, Debug)]
pub struct CaptureJob {
    /// Directory to write to.
    pub dir: PathBuf,
    /// File name without extension.
    pub stem: String,
    /// The display transform of the PNG.
    pub display: DisplaySettings,
}

/// One frame's outstanding work.
#[derive(Clone, Debug, Default)]
pub struct Pending {
    /// Its readbacks.
    pub readbacks: Readbacks,
    /// Where the HDR readback goes.
    pub capture: Option<CaptureJob>,
    /// Where the window readback goes.
    pub screenshot: Option<PathBuf>,
}

/// What finishing a frame produced.
#[derive(Debug, Default)]
pub struct Finished {
    /// A message for the user.
    pub message: Option<String>,
    /// The screenshot was written.
    pub screenshot_written: bool,
}

impl Pending {
    /// Writes the frame's captures. A failed F12 capture becomes a message; a failed screenshot
    /// is an error (it is what the run was for).
    pub fn finish(self, outputs: &FrameOutputs) -> anyhow::Result<Finished> {
        let mut finished = Finished::default();
        if let (Some(id), Some(job)) = (self.readbacks.hdr, self.capture) {
            let saved = outputs
                .image(id)
                .map_err(anyhow::Error::from)
                .and_then(|hdr| capture::save_capture(&job.dir, &job.stem, &hdr, &job.display));
            finished.message = Some(match saved {
                Ok([exr, png]) => format!("captured {} and {}", exr.display(), png.display()),
                Err(e) => format!("capture failed: {e:#}"),
            });
        }
        if let (Some(id), Some(path)) = (self.readbacks.screen, self.screenshot) {
            save_screenshot(outputs, id, &path)?;
            finished.screenshot_written = true;
        }
        Ok(finished)
    }
}

fn save_screenshot(
    outputs: &FrameOutputs,
    id: lucid_engine::graph::ReadbackId,
    path: &Path,
) -> anyhow::Result<()> {
    let image = outputs.image(id)?;
    capture::save_display_png(path, &image)
}
