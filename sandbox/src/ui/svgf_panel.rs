//! The SVGF denoiser's mode and parameters in the settings panel.

use lucid_passes::denoise::svgf::{SvgfMode, SvgfParams};

/// The modes the panel offers, by name (the budgets keep their current values when switched to).
fn mode_label(mode: SvgfMode) -> &'static str {
    match mode {
        SvgfMode::Temporal => "temporal (every frame)",
        SvgfMode::EveryFrame => "spatial, every frame",
        SvgfMode::AfterSamples(_) => "spatial, after N samples",
        SvgfMode::AfterSeconds(_) => "spatial, after a time budget",
    }
}

/// Edits `params`: the mode (with its sample or time budget) and the filter's parameters;
/// `gradients_available`: the light transport can replay paths for the temporal gradients.
pub fn svgf(ui: &mut egui::Ui, params: &mut SvgfParams, gradients_available: bool) {
    egui::CollapsingHeader::new("SVGF")
        .default_open(false)
        .show(ui, |ui| {
            egui::ComboBox::from_label("mode")
                .selected_text(mode_label(params.mode))
                .show_ui(ui, |ui| {
                    for mode in [
                        SvgfMode::Temporal,
                        SvgfMode::EveryFrame,
                        SvgfMode::AfterSamples(64),
                        SvgfMode::AfterSeconds(2.0),
                    ] {
                        let selected = mode_label(params.mode) == mode_label(mode);
                        if ui.selectable_label(selected, mode_label(mode)).clicked() && !selected {
                            params.mode = mode;
                        }
                    }
                });
            match &mut params.mode {
                SvgfMode::AfterSamples(n) => {
                    ui.add(
                        egui::DragValue::new(n)
                            .range(1..=1 << 20)
                            .prefix("samples: "),
                    );
                }
                SvgfMode::AfterSeconds(s) => {
                    ui.add(
                        egui::DragValue::new(s)
                            .range(0.0..=600.0)
                            .speed(0.1)
                            .suffix(" s"),
                    );
                }
                SvgfMode::Temporal | SvgfMode::EveryFrame => {}
            }
            ui.add(egui::Slider::new(&mut params.iterations, 1..=8).text("a-trous iterations"));
            ui.add(egui::Slider::new(&mut params.alpha, 0.01..=1.0).text("alpha (colour)"));
            ui.add(
                egui::Slider::new(&mut params.moments_alpha, 0.01..=1.0).text("alpha (moments)"),
            );
            ui.add(egui::Slider::new(&mut params.surface_alpha, 0.01..=1.0).text("alpha (albedo)"));
            ui.add(egui::Slider::new(&mut params.sigma_z, 0.1..=10.0).text("sigma z"));
            ui.add(egui::Slider::new(&mut params.sigma_n, 1.0..=256.0).text("sigma n"));
            ui.add(egui::Slider::new(&mut params.sigma_l, 0.5..=16.0).text("sigma l"));
            ui.checkbox(&mut params.firefly_clamp, "clamp fireflies")
                .on_hover_text("bound each sample by the history and samples around it: no lingering bright spots, but light found only by rare paths is lost");
            ui.add_enabled(
                params.firefly_clamp,
                egui::Slider::new(&mut params.firefly_headroom, 2.0..=64.0)
                    .logarithmic(true)
                    .text("firefly headroom"),
            );
            ui.checkbox(&mut params.gradients, "temporal gradients (A-SVGF)");
            if !gradients_available {
                ui.label("(this light transport cannot replay paths: history is rejected by geometry only)");
            }
            ui.checkbox(
                &mut params.gradients_every_frame,
                "replay gradient paths in a static scene too",
            );
            ui.add(egui::Slider::new(&mut params.gradient_stratum, 2..=8).text("gradient stratum"));
        });
}
