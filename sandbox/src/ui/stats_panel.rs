//! The live numbers: frame time and FPS, frame-time graph, GPU time per pass, samples and memory.

use super::charts;
use super::Readouts;

/// Shows the section.
pub fn show(ui: &mut egui::Ui, r: &Readouts<'_>) {
    egui::CollapsingHeader::new("Statistics")
        .default_open(true)
        .show(ui, |ui| {
            ui.label(format!("{} on {}", r.source, r.device));
            ui.label(format!("{} x {}", r.extent[0], r.extent[1]));
            ui.label(r.frame_rate.label());
            ui.label(format!("samples accumulated: {}", r.samples));
            ui.label("frame time (ms)");
            charts::line_graph(ui, &r.frame_times_ms);
            let total: f64 = r.pass_timings.iter().map(|t| t.ms).sum();
            ui.label(format!("GPU time per pass ({total:.3} ms)"));
            charts::bar_chart(ui, r.pass_timings);
            ui.label(format!(
                "GPU memory: {:.1} MiB allocated, {:.1} MiB reserved",
                mib(r.memory.allocated_bytes),
                mib(r.memory.reserved_bytes)
            ));
            for c in &r.memory.categories {
                ui.label(format!(
                    "  {}: {:.2} MiB in {}",
                    c.category,
                    mib(c.bytes),
                    c.allocations
                ));
            }
        });
}

fn mib(bytes: u64) -> f64 {
    bytes as f64 / (1024.0 * 1024.0)
}
