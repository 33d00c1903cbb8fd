//! The "Auto configuration" section: the goal of `--algo auto`, a button that (re-)runs the
//! calibration on the scene, and what it chose and why.

use super::Requests;
use crate::auto::{AutoState, GoalKind};
use lucid_passes::tradeoff::Metric;

/// Shows the section.
pub fn show(ui: &mut egui::Ui, auto: &mut AutoState, requests: &mut Requests) {
    ui.horizontal(|ui| {
        ui.radio_value(&mut auto.kind, GoalKind::Budget, "frame budget");
        ui.radio_value(&mut auto.kind, GoalKind::Quality, "quality target");
    });
    match auto.kind {
        GoalKind::Budget => ui.add(
            egui::DragValue::new(&mut auto.budget_ms)
                .range(0.01..=10_000.0)
                .speed(0.1)
                .suffix(" ms per frame"),
        ),
        GoalKind::Quality => ui.add(
            egui::DragValue::new(&mut auto.quality)
                .range(0.0..=100.0)
                .speed(0.005)
                .prefix("error at most "),
        ),
    };
    egui::ComboBox::from_label("error")
        .selected_text(auto.metric.label())
        .show_ui(ui, |ui| {
            for m in Metric::ALL {
                ui.selectable_value(&mut auto.metric, m, m.label());
            }
        });
    if ui
        .button("Calibrate")
        .on_hover_text(
            "Measure both algorithms with each denoiser at 1, 2 and 4 samples per pixel on this \
             view (fewer on a software device) and pick one; the window waits meanwhile",
        )
        .clicked()
    {
        requests.calibrate = true;
    }
    match &auto.last {
        None => {
            ui.label("not calibrated yet");
        }
        Some(Ok(calibrated)) => {
            let choice = &calibrated.choice;
            ui.label(format!(
                "chose {} for {} ({:.1} s)",
                choice.config.name(),
                calibrated.goal,
                calibrated.seconds
            ));
            ui.label(egui::RichText::new(&choice.reason).small());
        }
        Some(Err(e)) => {
            ui.colored_label(egui::Color32::LIGHT_RED, e);
        }
    }
}
