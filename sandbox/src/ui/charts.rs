//! Small charts drawn with egui's painter: a frame-time line graph and per-pass bars.

use egui::{Color32, Pos2, Rect, Sense, Stroke, Vec2};
use lucid_engine::graph::PassTiming;

const GRAPH_HEIGHT: f32 = 60.0;
const BAR_HEIGHT: f32 = 14.0;
const LINE: Color32 = Color32::from_rgb(110, 200, 120);
const BAR: Color32 = Color32::from_rgb(90, 140, 220);

/// A line graph of `values` (oldest first), scaled to its maximum, which is labelled.
pub fn line_graph(ui: &mut egui::Ui, values: &[f64]) {
    let (rect, _) = ui.allocate_exact_size(
        Vec2::new(ui.available_width(), GRAPH_HEIGHT),
        Sense::hover(),
    );
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, ui.visuals().extreme_bg_color);
    let max = values.iter().copied().fold(0.0, f64::max);
    if values.len() < 2 || max <= 0.0 {
        return;
    }
    let step = rect.width() / (values.len() - 1) as f32;
    let points: Vec<Pos2> = values
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            Pos2::new(
                rect.left() + i as f32 * step,
                rect.bottom() - (v / max) as f32 * (rect.height() - 2.0),
            )
        })
        .collect();
    painter.add(egui::Shape::line(points, Stroke::new(1.5, LINE)));
    painter.text(
        rect.left_top() + Vec2::new(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        format!("max {max:.2} ms"),
        egui::FontId::monospace(10.0),
        ui.visuals().text_color(),
    );
}

/// One horizontal bar per pass name, scaled to the slowest, with its name and time: passes that
/// share a name (the wavefront path tracer's kernels run once per bounce) are summed into one bar
/// marked with their count.
pub fn bar_chart(ui: &mut egui::Ui, timings: &[PassTiming]) {
    let bars = by_name(timings);
    let max = bars.iter().map(|b| b.1).fold(0.0, f64::max);
    for (name, ms, count) in bars {
        let (rect, _) =
            ui.allocate_exact_size(Vec2::new(ui.available_width(), BAR_HEIGHT), Sense::hover());
        let painter = ui.painter_at(rect);
        let fraction = if max > 0.0 { (ms / max) as f32 } else { 0.0 };
        let bar = Rect::from_min_size(
            rect.min,
            Vec2::new(rect.width() * fraction, rect.height() - 2.0),
        );
        painter.rect_filled(bar, 1.0, BAR);
        let times = if count > 1 {
            format!(" x{count}")
        } else {
            String::new()
        };
        painter.text(
            rect.left_center() + Vec2::new(2.0, -1.0),
            egui::Align2::LEFT_CENTER,
            format!("{name}{times} {ms:.3} ms"),
            egui::FontId::monospace(10.0),
            ui.visuals().strong_text_color(),
        );
    }
}

/// The passes' times summed by name, in the order the names first run: (name, ms, passes).
fn by_name(timings: &[PassTiming]) -> Vec<(&str, f64, usize)> {
    let mut bars: Vec<(&str, f64, usize)> = Vec::new();
    for t in timings {
        match bars.iter_mut().find(|b| b.0 == t.name) {
            Some(bar) => {
                bar.1 += t.ms;
                bar.2 += 1;
            }
            None => bars.push((&t.name, t.ms, 1)),
        }
    }
    bars
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_of_one_name_share_a_bar() {
        let timing = |name: &str, ms| PassTiming {
            name: name.into(),
            ms,
            start_ms: 0.0,
        };
        let timings = [
            timing("generate", 1.0),
            timing("extend", 2.0),
            timing("shade", 3.0),
            timing("extend", 0.5),
        ];
        assert_eq!(
            by_name(&timings),
            [("generate", 1.0, 1), ("extend", 2.5, 2), ("shade", 3.0, 1)]
        );
    }
}
