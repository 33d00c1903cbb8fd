//! What the UI adds to a split view: the divider between the halves and a label on each naming
//! its configuration, with its accumulated samples and GPU time.

use crate::frame_source::{split_column, SideStats};
use crate::settings::RenderSettings;
use egui::{Align2, Color32, FontId, LayerId, Pos2, Stroke};

/// The divider's colour.
pub const DIVIDER: Color32 = Color32::from_rgb(255, 200, 0);
/// The divider's width in points.
const DIVIDER_WIDTH: f32 = 2.0;
/// The labels' background.
const LABEL_BACKGROUND: Color32 = Color32::from_rgba_premultiplied(0, 0, 0, 200);
/// Space between the divider or the top and a label, in points.
const MARGIN: f32 = 8.0;

/// Draws the divider and labels over the image (`extent` pixels) where no panel covers it.
pub fn show(
    ctx: &egui::Context,
    extent: [u32; 2],
    settings: [&RenderSettings; 2],
    stats: [SideStats; 2],
) {
    let area = ctx.available_rect();
    let x = split_column(extent[0]) as f32 / ctx.pixels_per_point();
    let painter = ctx
        .layer_painter(LayerId::background())
        .with_clip_rect(area);
    painter.line_segment(
        [Pos2::new(x, area.top()), Pos2::new(x, area.bottom())],
        Stroke::new(DIVIDER_WIDTH, DIVIDER),
    );
    let top = area.top() + MARGIN;
    let anchors = [
        (Align2::RIGHT_TOP, Pos2::new(x - MARGIN, top), "left"),
        (Align2::LEFT_TOP, Pos2::new(x + MARGIN, top), "right"),
    ];
    for ((align, at, side), (settings, stats)) in
        anchors.into_iter().zip(settings.iter().zip(stats))
    {
        let text = format!(
            "{side}: {}\n{} spp accumulated, {:.2} ms",
            settings.summary(),
            stats.samples,
            stats.gpu_ms
        );
        let galley = painter.layout_no_wrap(text, FontId::proportional(13.0), Color32::WHITE);
        let rect = align.anchor_size(at, galley.size());
        painter.rect_filled(rect.expand(4.0), 3.0, LABEL_BACKGROUND);
        painter.galley(rect.min, galley, Color32::WHITE);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui::epaint::Shape;
    use egui::{Rect, Vec2};

    #[test]
    fn draws_the_divider_at_the_split_and_a_label_on_each_side() {
        let ctx = egui::Context::default();
        let input = egui::RawInput {
            screen_rect: Some(Rect::from_min_size(Pos2::ZERO, Vec2::new(800.0, 600.0))),
            ..Default::default()
        };
        let settings = RenderSettings::default();
        let stats = SideStats {
            samples: 12,
            gpu_ms: 1.5,
        };
        let output = ctx.run(input, |ctx| {
            show(
                ctx,
                [800, 600],
                [&settings, &settings.compared()],
                [stats; 2],
            );
        });
        let mut divider = None;
        let mut labels = Vec::new();
        for clipped in &output.shapes {
            match &clipped.shape {
                Shape::LineSegment { points, stroke } if stroke.color == DIVIDER => {
                    divider = Some(*points)
                }
                Shape::Text(text) => labels.push((text.pos.x, text.galley.text().to_string())),
                _ => {}
            }
        }
        let [top, bottom] = divider.expect("a divider");
        assert_eq!((top.x, bottom.x), (400.0, 400.0));
        assert_eq!((top.y, bottom.y), (0.0, 600.0));
        assert_eq!(labels.len(), 2, "{labels:?}");
        let (left, right) = (&labels[0], &labels[1]);
        assert!(
            left.0 < 400.0 && left.1.starts_with("left: path tracing"),
            "{left:?}"
        );
        assert!(
            right.0 > 400.0 && right.1.starts_with("right: bidirectional"),
            "{right:?}"
        );
        assert!(right.1.contains("12 spp accumulated, 1.50 ms"), "{right:?}");
    }
}
