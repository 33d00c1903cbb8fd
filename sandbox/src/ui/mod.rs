//! The egui panels: settings on the right, live numbers and charts below them, and the split
//! view's divider and labels over the image.

mod auto_panel;
mod charts;
mod settings_panel;
mod split_view;
mod stats_panel;
mod svgf_panel;

use super::frame_source::SideStats;
use super::state::AppState;
use super::stats::FrameRate;
use lucid_engine::graph::PassTiming;
use lucid_engine::memory::MemoryReport;

/// Numbers the panels show but do not edit.
pub struct Readouts<'a> {
    /// Frame time and frames per second.
    pub frame_rate: FrameRate,
    /// Recent frame times in milliseconds, oldest first.
    pub frame_times_ms: Vec<f64>,
    /// GPU time per pass of the last completed frame.
    pub pass_timings: &'a [PassTiming],
    /// Samples per pixel accumulated.
    pub samples: u64,
    /// GPU memory in use.
    pub memory: MemoryReport,
    /// The frame source's name.
    pub source: &'a str,
    /// The device's name.
    pub device: &'a str,
    /// The output size.
    pub extent: [u32; 2],
    /// The halves' numbers while the output is a split view.
    pub split: Option<[SideStats; 2]>,
}

/// What the user asked for with buttons this frame.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Requests {
    /// Load this scene (name or file).
    pub load_scene: Option<String>,
    /// Start recording a camera path.
    pub record: bool,
    /// Stop recording and save.
    pub stop: bool,
    /// Replay the path file.
    pub replay: bool,
    /// Capture the HDR output.
    pub capture: bool,
    /// Run the `--algo auto` calibration on the scene and switch to its choice.
    pub calibrate: bool,
}

/// Draws the panels; returns what the user asked for.
pub fn draw(ctx: &egui::Context, state: &mut AppState, readouts: &Readouts<'_>) -> Requests {
    let mut requests = Requests::default();
    egui::SidePanel::right("lucid.panel")
        .resizable(true)
        .default_width(300.0)
        .show(ctx, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                settings_panel::show(ui, state, &mut requests);
                stats_panel::show(ui, readouts);
            });
        });
    if let Some(message) = &state.message {
        egui::TopBottomPanel::bottom("lucid.message").show(ctx, |ui| {
            ui.label(message.as_str());
        });
    }
    if let (Some(right), Some(stats)) = (&state.split, readouts.split) {
        split_view::show(ctx, readouts.extent, [&state.render, right], stats);
    }
    requests
}
