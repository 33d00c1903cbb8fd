//! `lucid evaluate`: metrics of rendered sequences against their reference, per frame, as CSV and
//! an SVG plot.

use super::maps;
use super::render_options::exposure;
use super::sequence::{frame_path, Method, CONVERGED_REFERENCE, SECOND_REFERENCE};
use super::stability;
use anyhow::Context as _;
use clap::Args;
use lucid_engine::atomic_write::write_atomic;
use lucid_engine::capture::{self, ImageData, PngEncoding};
use lucid_engine::metrics::{evaluate_sequences, FrameMetrics, SequenceMetrics};
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Options of `lucid evaluate`.
#[derive(Debug, Args)]
pub struct EvaluateArgs {
    /// A folder written by `lucid sequence` (`reference/` and one folder per method).
    #[arg(default_value = "sequence")]
    dir: PathBuf,
    /// Exposure in stops of the display mapping SSIM and FLIP compare.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = exposure())]
    exposure: f32,
    /// Also map where each method flickers and where it differs: `maps/<method>.png` (per-pixel
    /// temporal instability, one colour scale for all), `maps/<method>.flip.png` (per-pixel FLIP
    /// averaged over the frames, likewise) and `maps/by_brightness.csv` (their shares by the
    /// reference's brightness, and the share of each band's light each method keeps).
    #[arg(long)]
    maps: bool,
    /// Evaluate only the first N frames (at least 2), as if the sequences had been rendered N
    /// frames long, into `DIR/first-N/` (the same files), so that one longer sequence also gives
    /// a shorter one's figures and its own stay.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(2..))]
    frames: Option<u32>,
}

/// Evaluates the folder.
pub fn run(args: &EvaluateArgs) -> anyhow::Result<()> {
    let display = PngEncoding {
        exposure: args.exposure,
        tone: capture::ToneCurve::Aces,
    };
    evaluate_folder(
        &args.dir,
        &display,
        args.maps,
        args.frames.map(|n| n as usize),
    )
}

/// Methods whose frames other programs write into a sequence folder, evaluated when present:
/// `oidn`, Intel Open Image Denoise run per frame (`training/oidn_baseline.py`).
pub const EXTERNAL_METHODS: [&str; 1] = ["oidn"];

/// Reads one metric from a frame's metrics.
type Metric = fn(&FrameMetrics) -> f64;

/// The metrics' names and how to read each.
const COLUMNS: [(&str, Metric); 5] = [
    ("rel_mse", |m| m.rel_mse),
    ("ssim", |m| m.ssim),
    ("dssim", |m| m.dssim),
    ("flip", |m| m.flip),
    ("temporal_instability", |m| m.temporal_instability),
];

/// Evaluates every method folder of `dir` against `dir/reference`, writing `metrics.csv` and
/// `metrics.svg` there (and `stability.svg`/`.png` where methods have GPU times, and with `maps`
/// the instability and FLIP maps, `maps.rs`) and printing the means. With `first`, only the first
/// that many frames of each folder, and the files go into `dir/first-<first>/`.
pub fn evaluate_folder(
    dir: &Path,
    display: &PngEncoding,
    maps: bool,
    first: Option<usize>,
) -> anyhow::Result<()> {
    let methods = method_folders(dir)?;
    let reference = load_frames(&dir.join("reference"), first)?;
    if let Some(first) = first {
        anyhow::ensure!(
            reference.len() == first,
            "reference/ has {} frames, fewer than the {first} to evaluate",
            reference.len()
        );
    }
    let frames = methods
        .iter()
        .map(|method| load_frames(&dir.join(method), first))
        .collect::<anyhow::Result<Vec<_>>>()?;
    for (method, frames) in methods.iter().zip(&frames) {
        anyhow::ensure!(
            frames.len() == reference.len(),
            "{method}/ has {} frames, reference/ {}",
            frames.len(),
            reference.len()
        );
    }
    let out_dir = match first {
        Some(first) => {
            let out_dir = dir.join(format!("first-{first}"));
            std::fs::create_dir_all(&out_dir)
                .with_context(|| format!("creating {}", out_dir.display()))?;
            out_dir
        }
        None => dir.to_path_buf(),
    };
    // Each reference frame is prepared once for every method, frames in parallel.
    let tests: Vec<&[ImageData]> = frames.iter().map(Vec::as_slice).collect();
    let metrics = evaluate_sequences(&tests, &reference, display)
        .with_context(|| format!("evaluating {}", methods.join(", ")))?;
    let results: Vec<(&str, SequenceMetrics)> =
        methods.iter().map(String::as_str).zip(metrics).collect();
    let csv = out_dir.join("metrics.csv");
    write_atomic(&csv, to_csv(&results).as_bytes())
        .with_context(|| format!("writing {}", csv.display()))?;
    let svg = out_dir.join("metrics.svg");
    write_atomic(&svg, to_svg(&results).as_bytes())
        .with_context(|| format!("writing {}", svg.display()))?;
    let chart = stability::write_chart(dir, &out_dir, &results)?;
    for (method, m) in &results {
        let means: Vec<String> = COLUMNS
            .iter()
            .map(|(name, get)| format!("{name} {:.4}", get(&m.mean)))
            .collect();
        println!("{method:>8}: {}", means.join(", "));
    }
    println!("-> {} and {}", csv.display(), svg.display());
    if maps {
        let (maps, folder) = maps::write(&out_dir, &methods, &frames, &reference, display)?;
        let bright = maps::BRIGHTNESS_EDGES[2];
        let brightest = maps::BRIGHTNESS_EDGES[3];
        for m in &maps {
            println!(
                "{:>8}: temporal instability {:.4}, {:.0}% of it from pixels over {bright}x the mean \
                 brightness; FLIP {:.4}, {:.0}% of it from them; {:.0}% of the light over \
                 {brightest}x kept",
                m.method,
                m.instability.map.mean(),
                100.0 * m.instability.share_from(bright),
                m.flip.map.mean(),
                100.0 * m.flip.share_from(bright),
                100.0 * m.light_kept_from(brightest),
            );
        }
        println!(
            "-> {} (where each method flickers and where it differs)",
            folder.display()
        );
    }
    if let Some(chart) = chart {
        println!(
            "-> {} (stability against GPU time per frame)",
            chart.display()
        );
    }
    Ok(())
}

/// The method folders of `dir` (the sequence's methods, then the learned denoiser's other weights'
/// `neural-*` in name order, then [`EXTERNAL_METHODS`], then [`SECOND_REFERENCE`] and
/// [`CONVERGED_REFERENCE`]) that exist; an error naming the expected folders when there is none.
fn method_folders(dir: &Path) -> anyhow::Result<Vec<String>> {
    anyhow::ensure!(dir.is_dir(), "{}: no such folder", dir.display());
    let extra_neural = format!("{}-", Method::Neural.name());
    let mut other_weights: Vec<String> = std::fs::read_dir(dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .filter_map(|entry| entry.ok()?.file_name().into_string().ok())
        .filter(|name| name.starts_with(&extra_neural))
        .collect();
    other_weights.sort();
    let expected: Vec<String> = Method::ALL
        .map(|m| m.name().to_owned())
        .into_iter()
        .chain(other_weights)
        .chain(EXTERNAL_METHODS.map(str::to_owned))
        .chain([SECOND_REFERENCE, CONVERGED_REFERENCE].map(str::to_owned))
        .collect();
    let present: Vec<String> = expected
        .iter()
        .filter(|method| dir.join(method).is_dir())
        .cloned()
        .collect();
    anyhow::ensure!(
        !present.is_empty(),
        "{}: no method folders to evaluate against reference/ (expected one or more of {})",
        dir.display(),
        expected
            .iter()
            .map(|m| format!("{m}/"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(present)
}

/// Frames `0000.exr`, `0001.exr`, ... of a folder, until the first missing one or the first
/// `first` (read in parallel).
fn load_frames(folder: &Path, first: Option<usize>) -> anyhow::Result<Vec<ImageData>> {
    let count = (0..first.unwrap_or(usize::MAX))
        .take_while(|&i| frame_path(folder, i).exists())
        .count();
    anyhow::ensure!(count > 0, "no frames in {}", folder.display());
    (0..count)
        .into_par_iter()
        .map(|i| {
            let path = frame_path(folder, i);
            capture::load_exr(&path).with_context(|| format!("reading {}", path.display()))
        })
        .collect()
}

/// One row per method and frame, then one `mean` row per method.
fn to_csv(results: &[(&str, SequenceMetrics)]) -> String {
    let mut out = String::from("method,frame");
    for (name, _) in COLUMNS {
        let _ = write!(out, ",{name}");
    }
    out.push('\n');
    for (method, m) in results {
        let rows = m
            .frames
            .iter()
            .enumerate()
            .map(|(i, f)| (i.to_string(), f))
            .chain(std::iter::once(("mean".to_string(), &m.mean)));
        for (frame, f) in rows {
            let _ = write!(out, "{method},{frame}");
            for (_, get) in COLUMNS {
                let _ = write!(out, ",{:.6}", get(f));
            }
            out.push('\n');
        }
    }
    out
}

/// One panel per metric (value against frame), one coloured line per method.
fn to_svg(results: &[(&str, SequenceMetrics)]) -> String {
    const W: f64 = 360.0;
    const H: f64 = 200.0;
    const PAD: f64 = 30.0;
    const COLOURS: [&str; 3] = ["#d62728", "#1f77b4", "#2ca02c"];
    let mut out = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" font-size="11">"#,
        W * 2.0,
        H * 3.0
    );
    out.push('\n');
    for (panel, (name, get)) in COLUMNS.iter().enumerate() {
        let (x0, y0) = ((panel % 2) as f64 * W, (panel / 2) as f64 * H);
        let series: Vec<Vec<f64>> = results
            .iter()
            .map(|(_, m)| m.frames.iter().map(get).collect())
            .collect();
        let max = series
            .iter()
            .flatten()
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
            .max(1e-9);
        let frames = series.first().map_or(1, Vec::len).max(2) as f64 - 1.0;
        let (left, top, width, height) = (x0 + PAD, y0 + PAD, W - 2.0 * PAD, H - 2.0 * PAD);
        let _ = writeln!(
            out,
            r##"<rect x="{left}" y="{top}" width="{width}" height="{height}" fill="none" stroke="#999"/>"##
        );
        let _ = writeln!(
            out,
            r#"<text x="{left}" y="{}">{name} (max {max:.4})</text>"#,
            top - 6.0
        );
        for (s, values) in series.iter().enumerate() {
            let points: Vec<String> = values
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    let x = x0 + PAD + i as f64 / frames * (W - 2.0 * PAD);
                    let y = y0 + H - PAD - (v / max).clamp(0.0, 1.0) * (H - 2.0 * PAD);
                    format!("{x:.1},{y:.1}")
                })
                .collect();
            let _ = writeln!(
                out,
                "<polyline fill=\"none\" stroke=\"{}\" points=\"{}\"/>",
                COLOURS[s % COLOURS.len()],
                points.join(" ")
            );
        }
    }
    for (s, (method, _)) in results.iter().enumerate() {
        let _ = writeln!(
            out,
            "<text x=\"{}\" y=\"{}\" fill=\"{}\">{method}</text>",
            W + PAD,
            2.0 * H + PAD + 16.0 * (s as f64 + 1.0),
            COLOURS[s % COLOURS.len()]
        );
    }
    out.push_str("</svg>\n");
    out
}
