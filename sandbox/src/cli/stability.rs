//! The stability chart of `lucid evaluate`: per method of a sequence, its temporal instability
//! and FLIP against its GPU time per frame (what `lucid sequence` measured while rendering it),
//! the Pareto fronts marked.

use super::converge_chart::{self, Panel};
use anyhow::Context as _;
use lucid_engine::atomic_write::write_atomic;
use lucid_engine::metrics::{FrameMetrics, SequenceMetrics};
use lucid_passes::tradeoff::pareto::pareto_front;
use std::path::{Path, PathBuf};

/// The file in a method's folder with its frames' GPU times, one millisecond figure a line.
pub const GPU_TIMES: &str = "gpu_ms.txt";

/// Writes `folder`'s [`GPU_TIMES`] (nothing where the device had no timestamps: all zero).
pub fn write_gpu_times(folder: &Path, times: &[f64]) -> anyhow::Result<()> {
    if times.iter().all(|&t| t == 0.0) {
        return Ok(());
    }
    let text: String = times.iter().map(|t| format!("{t}\n")).collect();
    let path = folder.join(GPU_TIMES);
    write_atomic(&path, text.as_bytes()).with_context(|| format!("writing {}", path.display()))
}

/// The median of a method folder's [`GPU_TIMES`], if the file is there.
fn median_gpu_ms(folder: &Path) -> anyhow::Result<Option<f64>> {
    let path = folder.join(GPU_TIMES);
    if !path.exists() {
        return Ok(None);
    }
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let mut times = text
        .lines()
        .map(|line| {
            line.trim()
                .parse::<f64>()
                .ok()
                .filter(|t| t.is_finite() && *t >= 0.0)
                .with_context(|| format!("{}: {line:?} is not a time in ms", path.display()))
        })
        .collect::<anyhow::Result<Vec<f64>>>()?;
    anyhow::ensure!(!times.is_empty(), "{}: no times", path.display());
    times.sort_by(f64::total_cmp);
    Ok(Some(times[times.len() / 2]))
}

/// Draws `out_dir/stability.png` and `.svg` from the methods with GPU times in their folders of
/// `dir` (methods rendered elsewhere, e.g. `oidn`, have none and are left out); returns the chart's
/// SVG path, or `None` when fewer than two methods have times.
pub fn write_chart(
    dir: &Path,
    out_dir: &Path,
    results: &[(&str, SequenceMetrics)],
) -> anyhow::Result<Option<PathBuf>> {
    let mut timed = Vec::new();
    for (method, metrics) in results {
        if let Some(ms) = median_gpu_ms(&dir.join(method))? {
            timed.push((method.to_string(), ms, metrics.mean));
        }
    }
    if timed.len() < 2 {
        return Ok(None);
    }
    let panel = |title: &str, label: &str, get: fn(&FrameMetrics) -> f64| {
        let points: Vec<(f64, f64)> = timed.iter().map(|(_, ms, m)| (*ms, get(m))).collect();
        Panel {
            title: format!("{title} (red: Pareto front)"),
            y_label: label.to_string(),
            front: pareto_front(&points),
            points: timed.iter().map(|(n, ..)| n.clone()).zip(points).collect(),
        }
    };
    let panels = [
        panel("temporal instability", "temporal instability", |m| {
            m.temporal_instability
        }),
        panel("FLIP", "FLIP", |m| m.flip),
    ];
    let chart = converge_chart::speed_vs_accuracy("GPU time per frame (ms)", &panels)?;
    let png = out_dir.join("stability.png");
    write_atomic(&png, &chart.png).with_context(|| format!("writing {}", png.display()))?;
    let svg = out_dir.join("stability.svg");
    write_atomic(&svg, chart.svg.as_bytes())
        .with_context(|| format!("writing {}", svg.display()))?;
    Ok(Some(svg))
}
