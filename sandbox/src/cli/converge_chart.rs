//! The charts of `lucid converge`, drawn with `plotters` as PNG (bitmap backend, encoded by
//! `image`) and SVG: error against time (log-log, a line per configuration), speed against
//! accuracy (a point per configuration, the Pareto front connected) and time to converge (a bar
//! per configuration).

use anyhow::anyhow;
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};
use plotters::coord::combinators::WithKeyPoints;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::sync::OnceLock;

/// The font every label uses: egui's Ubuntu Light, registered with plotters once (no system
/// fonts are looked up).
const FONT: &str = "sans-serif";

/// A chart as PNG bytes and SVG text.
pub struct Chart {
    /// The PNG file's bytes.
    pub png: Vec<u8>,
    /// The SVG document.
    pub svg: String,
}

/// One line of [`error_vs_time`]: a configuration's (time, error) measurements.
pub struct Series {
    /// The configuration, in the legend.
    pub name: String,
    /// (cumulative time in ms, error), by increasing time.
    pub points: Vec<(f64, f64)>,
}

/// One panel of [`speed_vs_accuracy`]: a metric's points and Pareto front.
pub struct Panel {
    /// The panel's caption.
    pub title: String,
    /// The error axis's label.
    pub y_label: String,
    /// Per configuration, its name and (time per frame, final error).
    pub points: Vec<(String, (f64, f64))>,
    /// Indices into `points` of the Pareto front, by increasing time.
    pub front: Vec<usize>,
}

/// One configuration of a [`time_to_converge`] panel.
pub struct Reached {
    /// The configuration, on the vertical axis.
    pub name: String,
    /// The time (ms) it first measured an error below the target; `None` if it never did.
    pub ms: Option<f64>,
    /// How long it ran (ms): where a configuration that never converged is marked.
    pub ran_ms: f64,
}

/// One panel of [`time_to_converge`]: a metric's target and every configuration's time to it.
pub struct ConvergePanel {
    /// The panel's caption.
    pub title: String,
    /// The configurations, top to bottom.
    pub entries: Vec<Reached>,
}

/// Error against time, log-log, a line (with a dot per measurement) per series, and the error
/// `target` (what "converged" means) as a dashed line.
pub fn error_vs_time(
    title: &str,
    x_label: &str,
    y_label: &str,
    target: f64,
    series: &[Series],
) -> anyhow::Result<Chart> {
    render(
        &ErrorVsTime {
            title,
            x_label,
            y_label,
            target,
            series,
        },
        (960, 640),
    )
}

/// One log-log panel per metric: a point per configuration, labelled, and the Pareto front
/// drawn as a red line through larger red points (the panel's title says so).
pub fn speed_vs_accuracy(x_label: &str, panels: &[Panel]) -> anyhow::Result<Chart> {
    let width = 520 * panels.len().max(1) as u32;
    render(&SpeedVsAccuracy { x_label, panels }, (width, 520))
}

/// One panel per metric: a horizontal bar per configuration to the time it converged at (log
/// time axis, labelled with the time), and a grey cross with `never in T ms` at the end of its run
/// for a configuration that never did.
pub fn time_to_converge(x_label: &str, panels: &[ConvergePanel]) -> anyhow::Result<Chart> {
    let rows = panels.iter().map(|p| p.entries.len()).max().unwrap_or(0) as u32;
    let width = 560 * panels.len().max(1) as u32;
    render(
        &TimeToConverge { x_label, panels },
        (width, (100 + 30 * rows).max(320)),
    )
}

/// Something plotters draws, onto any backend.
trait Figure {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>;
}

/// Draws `figure` at `size` as SVG and as PNG.
fn render(figure: &impl Figure, (width, height): (u32, u32)) -> anyhow::Result<Chart> {
    register_font()?;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        figure
            .draw(&root)
            .and_then(|()| root.present())
            .map_err(|e| anyhow!("drawing the SVG chart: {e}"))?;
    }
    let mut rgb = vec![255u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        figure
            .draw(&root)
            .and_then(|()| root.present())
            .map_err(|e| anyhow!("drawing the PNG chart: {e}"))?;
    }
    let mut png = Vec::new();
    PngEncoder::new(&mut png).write_image(&rgb, width, height, ExtendedColorType::Rgb8)?;
    Ok(Chart { png, svg })
}

/// Registers [`FONT`] with plotters (once per process).
fn register_font() -> anyhow::Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT)
            .is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the charts' font could not be loaded"))
    }
}

/// A log axis's range covering the positive finite `values`, with a margin of `margin` (a
/// factor) above.
fn log_range(values: impl Iterator<Item = f64>, margin: f64) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return 1e-3..1.0;
    }
    let (lo, hi) = if hi / lo < 1.5 {
        (lo / 1.5, hi * 1.5)
    } else {
        (lo, hi)
    };
    lo / 1.2..hi * margin
}

/// A log axis over `range` with labelled ticks at 1, 2 and 5 times powers of ten (every integer
/// multiple when that gives fewer than three) and grid lines at every integer multiple: plotters'
/// own log axis labels only whole powers of ten, none at all on a range within a decade.
fn log_axis(range: std::ops::Range<f64>) -> WithKeyPoints<LogCoord<f64>> {
    let (bold, light) = log_ticks(&range);
    range
        .log_scale()
        .with_key_points(bold)
        .with_light_points(light)
}

/// The labelled and the grid-only ticks of [`log_axis`].
fn log_ticks(range: &std::ops::Range<f64>) -> (Vec<f64>, Vec<f64>) {
    let multiples = |factors: &[u32]| -> Vec<f64> {
        let (first, last) = (
            range.start.log10().floor() as i32,
            range.end.log10().ceil() as i32,
        );
        (first..=last)
            .flat_map(|k| factors.iter().map(move |&m| f64::from(m) * 10f64.powi(k)))
            .filter(|v| range.contains(v))
            .collect()
    };
    let every: Vec<u32> = (1..=9).collect();
    let mut bold = multiples(&[1, 2, 5]);
    if bold.len() < 3 {
        bold = multiples(&every);
    }
    let light = multiples(&every)
        .into_iter()
        .filter(|v| !bold.contains(v))
        .collect();
    (bold, light)
}

/// Fills `root` white, splits it into one area per panel side by side (at least one) and draws
/// each panel into its area with `draw`.
fn side_by_side<DB: DrawingBackend, P>(
    root: &DrawingArea<DB, Shift>,
    panels: &[P],
    mut draw: impl FnMut(&P, &DrawingArea<DB, Shift>) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    for (panel, area) in panels
        .iter()
        .zip(&root.split_evenly((1, panels.len().max(1))))
    {
        draw(panel, area)?;
    }
    Ok(())
}

/// Log-log axes over `x` and `y`.
type LogLog = Cartesian2d<WithKeyPoints<LogCoord<f64>>, WithKeyPoints<LogCoord<f64>>>;

/// A chart on `area` with log axes over `x` and `y`, its caption (text and font size) and its
/// mesh drawn: tick labels of font size `text`, the axes' descriptions one size larger.
fn log_log_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    (caption, caption_size): (&str, u32),
    (x_label, y_label): (&str, &str),
    (x, y): (std::ops::Range<f64>, std::ops::Range<f64>),
    text: u32,
) -> Result<ChartContext<'a, DB, LogLog>, DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, caption_size))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(log_axis(x), log_axis(y))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style((FONT, text))
        .axis_desc_style((FONT, text + 1))
        .draw()?;
    Ok(chart)
}

/// Whether a point can be drawn on log-log axes.
fn drawable(&(x, y): &(f64, f64)) -> bool {
    x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0
}

/// A tick label: about two significant digits, whatever the decade.
fn tick(v: &f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".to_string()
    } else if a >= 100.0 {
        format!("{v:.0}")
    } else if a >= 1e-4 {
        let decimals = (1.0 - a.log10().floor()).clamp(0.0, 6.0) as usize;
        let text = format!("{v:.decimals$}");
        match text.contains('.') {
            true => text.trim_end_matches('0').trim_end_matches('.').to_string(),
            false => text,
        }
    } else {
        format!("{v:.0e}")
    }
}

struct ErrorVsTime<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    target: f64,
    series: &'a [Series],
}

impl Figure for ErrorVsTime<'_> {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        root.fill(&WHITE)?;
        let all = || self.series.iter().flat_map(|s| s.points.iter().copied());
        let x = log_range(all().map(|p| p.0), 1.2);
        let axis_x = x.clone();
        let y = log_range(all().map(|p| p.1).chain([self.target]), 1.2);
        let mut chart = log_log_chart(
            root,
            (self.title, 22),
            (self.x_label, self.y_label),
            (axis_x, y),
            14,
        )?;
        if drawable(&(x.start, self.target)) {
            let grey = RGBColor(110, 110, 110);
            chart
                .draw_series(DashedLineSeries::new(
                    [(x.start, self.target), (x.end, self.target)],
                    8,
                    6,
                    grey.stroke_width(1),
                ))?
                .label(format!("target {}", self.target))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], grey));
        }
        for (i, series) in self.series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let points: Vec<(f64, f64)> = series.points.iter().copied().filter(drawable).collect();
            chart
                .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?
                .label(series.name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FONT, 13))
            .draw()?;
        Ok(())
    }
}

struct SpeedVsAccuracy<'a> {
    x_label: &'a str,
    panels: &'a [Panel],
}

impl Figure for SpeedVsAccuracy<'_> {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        side_by_side(root, self.panels, |panel, area| {
            draw_speed_vs_accuracy(panel, self.x_label, area)
        })
    }
}

/// One panel of [`speed_vs_accuracy`]: the points, the Pareto front connected and named larger.
fn draw_speed_vs_accuracy<DB: DrawingBackend>(
    panel: &Panel,
    x_label: &str,
    area: &DrawingArea<DB, Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    // Room on the right and above for the points' names.
    let x = log_range(panel.points.iter().map(|(_, p)| p.0), 2.0);
    let y = log_range(panel.points.iter().map(|(_, p)| p.1), 1.3);
    let mut chart = log_log_chart(
        area,
        (&panel.title, 20),
        (x_label, &panel.y_label),
        (x, y),
        13,
    )?;
    let front: Vec<(f64, f64)> = panel
        .front
        .iter()
        .filter_map(|&i| panel.points.get(i).map(|(_, p)| *p))
        .filter(drawable)
        .collect();
    chart.draw_series(LineSeries::new(front, RED.stroke_width(2)))?;
    let others = panel
        .points
        .iter()
        .enumerate()
        .filter(|(i, (_, p))| !panel.front.contains(i) && drawable(p));
    chart.draw_series(others.map(|(_, (name, p))| {
        EmptyElement::at(*p)
            + Circle::new((0, 0), 4, BLUE.mix(0.7).filled())
            + Text::new(name.clone(), (6, -14), (FONT, 12).into_font())
    }))?;
    let on_front = panel
        .front
        .iter()
        .filter_map(|&i| panel.points.get(i))
        .filter(|(_, p)| drawable(p));
    chart.draw_series(on_front.map(|(name, p)| {
        EmptyElement::at(*p)
            + Circle::new((0, 0), 6, RED.filled())
            + Text::new(name.clone(), (7, -16), (FONT, 13).into_font())
    }))?;
    Ok(())
}

struct TimeToConverge<'a> {
    x_label: &'a str,
    panels: &'a [ConvergePanel],
}

impl Figure for TimeToConverge<'_> {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        side_by_side(root, self.panels, |panel, area| {
            draw_time_to_converge(panel, self.x_label, area)
        })
    }
}

/// One panel of [`time_to_converge`]: a slot per entry, the first at the top.
fn draw_time_to_converge<DB: DrawingBackend>(
    panel: &ConvergePanel,
    x_label: &str,
    area: &DrawingArea<DB, Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let count = panel.entries.len() as i32;
    let times = panel
        .entries
        .iter()
        .flat_map(|e| e.ms.into_iter().chain([e.ran_ms]));
    // Room on the right for the labels.
    let x = log_range(times, 4.0);
    let left = x.start;
    let slot = |i: usize| count - 1 - i as i32;
    let names: Vec<&str> = panel.entries.iter().map(|e| e.name.as_str()).collect();
    let name_of = |v: &SegmentValue<i32>| match v {
        SegmentValue::CenterOf(y) | SegmentValue::Exact(y) => usize::try_from(count - 1 - y)
            .ok()
            .and_then(|i| names.get(i))
            .map_or(String::new(), |n| n.to_string()),
        SegmentValue::Last => String::new(),
    };
    let longest = names.iter().map(|n| n.len()).max().unwrap_or(0) as u32;
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, (FONT, 20))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(16 + 7 * longest)
        // Integer ranges include their end: one slot per entry.
        .build_cartesian_2d(log_axis(x), (0..(count - 1).max(0)).into_segmented())?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .x_label_formatter(&tick)
        .y_label_formatter(&name_of)
        .disable_y_mesh()
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .draw()?;
    let reached: Vec<(i32, f64)> = panel
        .entries
        .iter()
        .enumerate()
        .filter_map(|(i, e)| {
            e.ms.filter(|ms| drawable(&(*ms, 1.0)))
                .map(|ms| (slot(i), ms))
        })
        .collect();
    chart.draw_series(reached.iter().map(|&(y, ms)| {
        let mut bar = Rectangle::new(
            [
                (left, SegmentValue::Exact(y)),
                (ms, SegmentValue::Exact(y + 1)),
            ],
            BLUE.mix(0.6).filled(),
        );
        bar.set_margin(4, 4, 0, 0);
        bar
    }))?;
    chart.draw_series(reached.iter().map(|&(y, ms)| {
        EmptyElement::at((ms, SegmentValue::CenterOf(y)))
            + Text::new(tick(&ms), (5, -7), (FONT, 12).into_font())
    }))?;
    let never = panel
        .entries
        .iter()
        .enumerate()
        .filter(|(_, e)| e.ms.is_none() && drawable(&(e.ran_ms, 1.0)));
    let grey = RGBColor(110, 110, 110);
    chart.draw_series(never.map(|(i, e)| {
        EmptyElement::at((e.ran_ms, SegmentValue::CenterOf(slot(i))))
            + Cross::new((0, 0), 5, grey.stroke_width(2))
            + Text::new(
                format!("never in {} ms", tick(&e.ran_ms)),
                (8, -7),
                (FONT, 12).into_font().color(&grey),
            )
    }))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charts_render_as_png_and_svg() {
        let series = [
            Series {
                name: "pt/none/1".into(),
                points: vec![(1.0, 0.5), (2.0, 0.3), (4.0, 0.2)],
            },
            // A single point, a zero and a NaN are drawn (or left out) without failing.
            Series {
                name: "pt/svgf/1".into(),
                points: vec![(1.5, 0.1), (3.0, 0.0), (5.0, f64::NAN)],
            },
        ];
        let chart = error_vs_time("DSSIM", "GPU time (ms)", "DSSIM", 0.1, &series).unwrap();
        assert!(chart.png.starts_with(b"\x89PNG"));
        assert!(chart.svg.contains("<svg") && chart.svg.contains("pt/svgf/1"));
        assert!(chart.svg.contains("target 0.1"));
        let panel = Panel {
            title: "final DSSIM (red: Pareto front)".into(),
            y_label: "DSSIM".into(),
            points: vec![("a".into(), (1.0, 0.5)), ("b".into(), (2.0, 0.1))],
            front: vec![0, 1],
        };
        let chart = speed_vs_accuracy("GPU time per frame (ms)", &[panel]).unwrap();
        assert!(chart.png.starts_with(b"\x89PNG"));
        assert!(chart.svg.contains("Pareto front") && chart.svg.contains("\nb\n"));
        let empty = error_vs_time("none", "x", "y", f64::NAN, &[]).unwrap();
        assert!(empty.png.starts_with(b"\x89PNG"));
    }

    #[test]
    fn times_to_converge_are_bars_and_the_configurations_that_never_converge_are_marked() {
        let entry = |name: &str, ms, ran_ms| Reached {
            name: name.into(),
            ms,
            ran_ms,
        };
        let panel = ConvergePanel {
            title: "GPU time to DSSIM < 0.1".into(),
            entries: vec![
                entry("pt/none/1", Some(700.0), 1300.0),
                entry("pt/svgf/1", Some(15.0), 1300.0),
                entry("bdpt/none/1", None, 1300.0),
            ],
        };
        let chart = time_to_converge("GPU time (ms)", &[panel]).unwrap();
        assert!(chart.png.starts_with(b"\x89PNG"));
        for text in [
            "pt/svgf/1",
            "bdpt/none/1",
            "never in 1300 ms",
            "\n700\n",
            "\n15\n",
        ] {
            assert!(chart.svg.contains(text), "{text} missing");
        }
        assert_eq!(
            chart.svg.matches("<rect").count(),
            1 + 2,
            "background and two bars"
        );
        let nothing = ConvergePanel {
            title: "none".into(),
            entries: Vec::new(),
        };
        let empty = time_to_converge("x", &[nothing]).unwrap();
        assert!(empty.png.starts_with(b"\x89PNG"));
    }

    #[test]
    fn log_axes_label_one_two_five_or_every_multiple_in_a_narrow_range() {
        let (bold, light) = log_ticks(&(0.03..3.0));
        assert_eq!(bold, [0.05, 0.1, 0.2, 0.5, 1.0, 2.0]);
        assert!(light.contains(&0.04) && !light.contains(&0.1));
        let (narrow, _) = log_ticks(&(0.15..0.45));
        assert_eq!(narrow, [0.2, 0.30000000000000004, 0.4]);
    }

    #[test]
    fn ticks_are_short() {
        assert_eq!(tick(&250.0), "250");
        assert_eq!(tick(&2.5), "2.5");
        assert_eq!(tick(&0.0123), "0.012");
        assert_eq!(tick(&3e-6), "3e-6");
        assert_eq!(tick(&0.8), "0.8");
        assert_eq!(tick(&1.0), "1");
    }
}
