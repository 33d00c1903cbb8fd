//! `lucid converge`: error against GPU time as samples accumulate, for every configuration
//! (algorithm x denoiser x samples per pixel per frame) of one scene seen by a still camera,
//! against a many-sample reference (rendered, or a file), measured at the same ladder of GPU times
//! for every configuration (`Schedule::TimeLadder`); written as CSV, JSON and charts
//! (`converge_chart.rs`). Another renderer's images join the charts with `--external`
//! (`external_series.rs`).

use super::converge_chart::{self, Series};
use super::external_series::{self, ExternalArg, ExternalResult};
use super::float_range::finite_f64;
use super::lists::{spp_list, value_list, List};
use super::output_path;
use super::progress::Progress;
use super::render_options::{exposure, samples_per_pixel};
use super::scene_source;
use super::size::Size;
use anyhow::Context as _;
use clap::Args;
use lucid_engine::atomic_write::write_atomic;
use lucid_engine::capture::{self, PngEncoding, ToneCurve};
use lucid_engine::metrics::PreparedReference;
use lucid_engine::{Context, ContextDesc};
use lucid_passes::denoise::neural::{InferencePath, NetworkWeights};
use lucid_passes::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_passes::tradeoff::measure::{measure, render_reference, REFERENCE_SPP_PER_FRAME};
use lucid_passes::tradeoff::pareto::{pareto_front, time_to_converge};
use lucid_passes::tradeoff::{Clock, Config, ConfigResult, Limits, Measurement, Metric, Schedule};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Options of `lucid converge`.
#[derive(Debug, Args)]
pub struct ConvergeArgs {
    /// A built-in scene (see `lucid scenes`) or a .gltf/.glb file; its camera stays still.
    #[arg(long, default_value = "cornell-box")]
    scene: String,
    /// Image size.
    #[arg(long, default_value = "512x512")]
    size: Size,
    /// Longest path (Mitsuba's convention: 1 = emitters only, 2 = direct light, ...).
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=1024))]
    max_depth: u32,
    /// Seed of the random numbers (the reference uses another).
    #[arg(long, default_value_t = 0)]
    seed: u32,
    /// Light-transport algorithms, comma-separated (bdpt is skipped, with a note, on a device
    /// without 64-bit integer atomics).
    #[arg(long, default_value = "pt,bdpt", value_parser = value_list::<Algorithm>("algorithm"))]
    algos: List<Algorithm>,
    /// Denoisers, comma-separated.
    #[arg(
        long,
        default_value = "none,svgf,neural",
        value_parser = value_list::<Denoiser>("denoiser")
    )]
    denoisers: List<Denoiser>,
    /// Samples per pixel per frame, comma-separated.
    #[arg(long, default_value = "1,2,4", value_parser = spp_list())]
    spp: List<SamplesPerPixel>,
    /// GPU time each configuration may spend, in milliseconds (the sum of its frames' pass times;
    /// wall time on a device without timestamp queries). Every configuration is measured at the
    /// first frame to reach each step of a ladder of times up to it: 1, 1.5, 2, 3, 5 and 7 times
    /// powers of ten from a thousandth of the budget, and the budget itself.
    #[arg(long, default_value_t = 1000.0, value_parser = finite_f64(1e-3, 1e9))]
    budget_ms: f64,
    /// Frames each configuration renders first, not measured (pipeline creation, caches), before
    /// it starts afresh (accumulation and histories reset).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(0..=1000))]
    warmup: u32,
    /// Most frames per configuration, whatever the budget.
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    max_frames: u32,
    /// Samples per pixel of the reference (path tracing, no denoiser), rendered once.
    #[arg(long, default_value = "1024", value_parser = samples_per_pixel(u32::MAX.into()))]
    reference_spp: SamplesPerPixel,
    /// The reference as an image file (.exr, linear; the size of --size) instead of rendering
    /// one, e.g. another renderer's many-sample image.
    #[arg(long, conflicts_with = "reference_spp")]
    reference: Option<PathBuf>,
    /// Another renderer's series, `NAME=FILE` (repeatable): FILE is JSON listing images with
    /// their samples per pixel and times (`bench/mitsuba/converge_cornell.py` writes one),
    /// measured against the same reference and drawn on the error-against-time charts.
    #[arg(long)]
    external: Vec<ExternalArg>,
    /// The DSSIM a configuration has converged at (its time to converge: when it first falls below).
    #[arg(long, default_value_t = 0.1, value_parser = finite_f64(0.0, 1e9))]
    target_dssim: f64,
    /// The FLIP a configuration has converged at.
    #[arg(long, default_value_t = 0.1, value_parser = finite_f64(0.0, 1.0))]
    target_flip: f64,
    /// The relative MSE a configuration has converged at.
    #[arg(long, default_value_t = 0.01, value_parser = finite_f64(0.0, 1e9))]
    target_relmse: f64,
    /// Exposure in stops of the display mapping SSIM and FLIP compare (as `lucid evaluate`).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = exposure())]
    exposure: f32,
    /// Weights of the learned denoiser (a file `training/train.py` wrote) instead of the
    /// committed ones.
    #[arg(long)]
    neural_weights: Option<PathBuf>,
    /// Output folder: `converge.csv`, `converge.json`, `error_vs_time_<metric>.png/.svg`,
    /// `speed_vs_accuracy.png/.svg` and `time_to_converge.png/.svg`.
    #[arg(long, default_value = "converge")]
    out: PathBuf,
    /// Print the JSON summary to stdout instead of the table.
    #[arg(long)]
    json: bool,
}

/// Runs the measurement and writes its files.
pub fn run(args: &ConvergeArgs) -> anyhow::Result<()> {
    output_path::create_folder("--out", &args.out)?;
    let weights = match &args.neural_weights {
        Some(path) => Some(NetworkWeights::load(path)?),
        None => None,
    };
    let (w, h) = (args.size.width, args.size.height);
    let display = PngEncoding {
        exposure: args.exposure,
        tone: ToneCurve::Aces,
    };
    let reference_file = match &args.reference {
        Some(path) => Some(load_reference(path, (w, h), &display)?),
        None => None,
    };
    let externals = args
        .external
        .iter()
        .map(|arg| external_series::read(arg, (w, h)))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let scene = scene_source::load(&args.scene, None)?;
    let ctx = Context::new(&ContextDesc::from_env())?;
    let device = ctx.info().name.clone();
    let mut notes = Vec::new();
    let mut algorithms = args.algos.0.clone();
    if !ctx.info().int64_atomics && algorithms.contains(&Algorithm::Bidirectional) {
        algorithms.retain(|a| *a != Algorithm::Bidirectional);
        notes.push(format!(
            "bdpt skipped: {device} has no 64-bit integer atomics (its light tracing splats need them)"
        ));
    }
    anyhow::ensure!(
        !algorithms.is_empty(),
        "no algorithm left to measure on {device}: {}",
        notes.join("; ")
    );
    let clock = Clock::of(&ctx);
    if clock == Clock::Wall {
        notes.push(format!(
            "{device} has no timestamp queries on its compute queue: times are wall times \
             (submission to completion), not GPU times"
        ));
    }
    for note in &notes {
        eprintln!("note: {note}");
    }
    let configs = Config::all(&algorithms, &args.denoisers.0, &args.spp.0);
    let base = Settings {
        max_depth: args.max_depth,
        seed: args.seed,
        accumulate: true,
        display,
        ..Settings::default()
    };
    let mut renderer = Renderer::new(&ctx, scene, w, h, base)?;
    if let Some(weights) = &weights {
        renderer.set_neural_network(weights, InferencePath::best(&ctx))?;
    }
    let reference = match reference_file {
        Some(reference) => reference,
        None => {
            let frames = args
                .reference_spp
                .get()
                .div_ceil(REFERENCE_SPP_PER_FRAME.get());
            eprintln!(
                "reference: {} spp in {frames} frames",
                args.reference_spp.get()
            );
            let progress = Progress::new(u64::from(frames), "reference frames");
            let reference = render_reference(
                &mut renderer,
                base,
                Algorithm::PathTracing,
                args.reference_spp,
                &mut || progress.inc(),
            )?;
            progress.finish();
            reference
        }
    };
    let externals = externals
        .iter()
        .map(|series| series.measure(&reference))
        .collect::<anyhow::Result<Vec<_>>>()?;
    eprintln!(
        "{} configurations, up to {} frames or {} ms each",
        configs.len(),
        args.max_frames,
        args.budget_ms
    );
    let progress = Progress::new(configs.len() as u64 * u64::from(args.max_frames), "frames");
    let limits = Limits {
        warmup: args.warmup,
        max_frames: args.max_frames,
        budget_ms: args.budget_ms,
    };
    let mut results = Vec::new();
    for config in &configs {
        let result = measure(
            &mut renderer,
            config.apply(base),
            &reference,
            limits,
            Schedule::TimeLadder,
            clock,
            &mut || progress.inc(),
        )
        .with_context(|| format!("measuring {}", config.name()))?;
        progress.inc_by(u64::from(args.max_frames - result.frames));
        results.push(result);
    }
    progress.finish();
    let targets = [
        (Metric::Dssim, args.target_dssim),
        (Metric::Flip, args.target_flip),
        (Metric::RelMse, args.target_relmse),
    ];
    let summary = Summary {
        args,
        device: &device,
        scene: &renderer.scene().name,
        clock,
        notes: &notes,
        targets,
        results: &results,
        externals: &externals,
    };
    let json = summary.to_json();
    write(
        &args.out.join("converge.csv"),
        to_csv(&results, &externals).as_bytes(),
    )?;
    write(
        &args.out.join("converge.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    write_charts(&args.out, &results, &externals, clock, |m| {
        summary.target(m)
    })?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        print!("{}", summary.table());
        println!("-> {}", args.out.display());
    }
    Ok(())
}

/// The reference from a file: `size`, finite, prepared with `display`.
fn load_reference(
    path: &Path,
    size: (u32, u32),
    display: &PngEncoding,
) -> anyhow::Result<PreparedReference> {
    let image = capture::load(path).context("loading --reference")?;
    anyhow::ensure!(
        (image.width, image.height) == size,
        "--reference {} is {}x{}, --size {}x{}",
        path.display(),
        image.width,
        image.height,
        size.0,
        size.1
    );
    anyhow::ensure!(
        !image.has_non_finite(),
        "--reference {} has NaN or infinite pixels",
        path.display()
    );
    PreparedReference::new(&image, display)
        .with_context(|| format!("preparing --reference {}", path.display()))
}

fn write(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    write_atomic(path, bytes).with_context(|| format!("writing {}", path.display()))
}

/// The CSV's header.
pub const CSV_HEADER: &str =
    "config,algo,denoiser,spp,frame,target_ms,gpu_ms,frame_ms,dssim,flip,rel_mse";

/// One line per measurement; numbers in full precision (what the JSON's times to converge are
/// computed from). `target_ms` is the step of the time ladder the line was measured for (empty
/// for a last frame that reached none), `gpu_ms` the time actually accumulated then (at most
/// `frame_ms`, its last frame's time, past the target). An external series' lines have its name
/// as the configuration, no algorithm, denoiser or target, its images' samples per pixel and
/// frame 1 (each image is one render).
fn to_csv(results: &[ConfigResult], externals: &[ExternalResult]) -> String {
    let mut out = format!("{CSV_HEADER}\n");
    let mut line = |config: &str, algo: &str, denoiser: &str, spp: u32, row: &Measurement| {
        let target = row.target_ms.map_or(String::new(), |t| t.to_string());
        let _ = writeln!(
            out,
            "{config},{algo},{denoiser},{spp},{},{target},{},{},{},{},{}",
            row.frame, row.gpu_ms, row.frame_ms, row.dssim, row.flip, row.rel_mse
        );
    };
    for r in results {
        let c = r.config;
        for row in &r.rows {
            line(
                &c.name(),
                c.algorithm.short_name(),
                c.denoiser.short_name(),
                c.spp.get(),
                row,
            );
        }
    }
    for e in externals {
        for p in &e.points {
            line(&csv_field(&e.name), "", "", p.spp, &p.measurement);
        }
    }
    out
}

/// `name` as a CSV field: quoted when it holds a comma or a quote.
fn csv_field(name: &str) -> String {
    if name.contains([',', '"']) {
        format!("\"{}\"", name.replace('"', "\"\""))
    } else {
        name.to_string()
    }
}

/// Everything the JSON and the printed table say.
struct Summary<'a> {
    args: &'a ConvergeArgs,
    device: &'a str,
    scene: &'a str,
    clock: Clock,
    notes: &'a [String],
    targets: [(Metric, f64); 3],
    results: &'a [ConfigResult],
    externals: &'a [ExternalResult],
}

impl Summary<'_> {
    /// Per metric, the Pareto front of (ms per frame, final error): configuration indices.
    fn fronts(&self) -> [(Metric, Vec<usize>); 3] {
        Metric::ALL.map(|metric| (metric, pareto_front(&speed_accuracy(self.results, metric))))
    }

    fn to_json(&self) -> serde_json::Value {
        use serde_json::{json, Map, Value};
        let per_metric = |f: &dyn Fn(Metric) -> Value| -> Value {
            Value::Object(
                Metric::ALL
                    .iter()
                    .map(|&m| (m.name().to_string(), f(m)))
                    .collect::<Map<_, _>>(),
            )
        };
        let fronts = self.fronts();
        let on_front = |metric: Metric, index: usize| {
            fronts
                .iter()
                .any(|(m, front)| *m == metric && front.contains(&index))
        };
        let configurations: Vec<Value> = self
            .results
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let c = r.config;
                json!({
                    "config": c.name(),
                    "algo": c.algorithm.short_name(),
                    "denoiser": c.denoiser.short_name(),
                    "spp": c.spp.get(),
                    "frames": r.frames,
                    "gpu_ms": r.gpu_ms,
                    "gpu_ms_per_frame": r.ms_per_frame(),
                    "final": per_metric(&|m| json!(r.last().map(|row| m.of(row)))),
                    "time_to_converge_ms": per_metric(&|m| {
                        let target = self.target(m);
                        json!(time_to_converge(&r.rows, m, target))
                    }),
                    "pareto": per_metric(&|m| json!(on_front(m, i))),
                    "rows": r.rows.iter().map(|row| json!({
                        "frame": row.frame,
                        "target_ms": row.target_ms,
                        "gpu_ms": row.gpu_ms,
                        "frame_ms": row.frame_ms,
                        "dssim": row.dssim,
                        "flip": row.flip,
                        "rel_mse": row.rel_mse,
                    })).collect::<Vec<_>>(),
                })
            })
            .collect();
        let externals: Vec<Value> = self
            .externals
            .iter()
            .map(|e| {
                let rows = e.rows();
                json!({
                    "name": e.name,
                    "renderer": e.renderer,
                    "device": e.device,
                    "time": e.time,
                    "file": e.file.display().to_string(),
                    "time_to_converge_ms": per_metric(&|m| json!(time_to_converge(&rows, m, self.target(m)))),
                    "points": e.points.iter().map(|p| json!({
                        "spp": p.spp,
                        "ms": p.measurement.gpu_ms,
                        "dssim": p.measurement.dssim,
                        "flip": p.measurement.flip,
                        "rel_mse": p.measurement.rel_mse,
                    })).collect::<Vec<_>>(),
                })
            })
            .collect();
        let args = self.args;
        let reference = match &args.reference {
            Some(path) => format!("the file {}", path.display()),
            None => {
                "path tracing, no denoiser, seed xor 0x9e3779b9, 16 samples per frame accumulated"
                    .to_string()
            }
        };
        let time = match self.clock {
            Clock::Gpu => "gpu",
            Clock::Wall => "wall",
        };
        json!({
            "command": std::env::args().collect::<Vec<_>>().join(" "),
            "device": self.device,
            "scene": self.scene,
            "size": [args.size.width, args.size.height],
            "max_depth": args.max_depth,
            "seed": args.seed,
            "reference_spp": args.reference.is_none().then(|| args.reference_spp.get()),
            "budget_ms": args.budget_ms,
            "time_ladder_ms": Schedule::TimeLadder.targets(args.budget_ms),
            "max_frames": args.max_frames,
            "warmup": args.warmup,
            "reference": reference,
            "time": time,
            "exposure": args.exposure,
            "notes": self.notes,
            "targets": per_metric(&|m| json!(self.target(m))),
            "pareto_front": per_metric(&|m| {
                let (_, front) = fronts.iter().find(|(f, _)| *f == m).expect("every metric");
                json!(front.iter().map(|&i| self.results[i].config.name()).collect::<Vec<_>>())
            }),
            "configurations": configurations,
            "external": externals,
        })
    }

    fn target(&self, metric: Metric) -> f64 {
        self.targets
            .iter()
            .find(|(m, _)| *m == metric)
            .map_or(f64::NAN, |(_, t)| *t)
    }

    /// A table for people: per configuration, frames, time per frame, final errors and times to
    /// converge (`-` for never), `*` after an error on that metric's Pareto front.
    fn table(&self) -> String {
        let fronts = self.fronts();
        let unit = match self.clock {
            Clock::Gpu => "GPU ms",
            Clock::Wall => "wall ms",
        };
        let mut out = format!(
            "{:<16} {:>6} {:>10} {:>10} {:>10} {:>10}   time to converge ({unit}): dssim<{} flip<{} rel_mse<{}\n",
            "config",
            "frames",
            "ms/frame",
            "dssim",
            "flip",
            "rel_mse",
            self.target(Metric::Dssim),
            self.target(Metric::Flip),
            self.target(Metric::RelMse),
        );
        for (i, r) in self.results.iter().enumerate() {
            let error = |m: Metric| {
                let star = fronts
                    .iter()
                    .any(|(f, front)| *f == m && front.contains(&i));
                let value = r.last().map_or(f64::NAN, |row| m.of(row));
                format!("{value:.4}{}", if star { "*" } else { " " })
            };
            let times: Vec<String> = Metric::ALL
                .iter()
                .map(|&m| match time_to_converge(&r.rows, m, self.target(m)) {
                    Some(ms) => format!("{ms:.1}"),
                    None => "-".to_string(),
                })
                .collect();
            let _ = writeln!(
                out,
                "{:<16} {:>6} {:>10.3} {:>10} {:>10} {:>10}   {}",
                r.config.name(),
                r.frames,
                r.ms_per_frame(),
                error(Metric::Dssim),
                error(Metric::Flip),
                error(Metric::RelMse),
                times.join(" / ")
            );
        }
        for e in self.externals {
            let rows = e.rows();
            let times: Vec<String> = Metric::ALL
                .iter()
                .map(|&m| match time_to_converge(&rows, m, self.target(m)) {
                    Some(ms) => format!("{ms:.1}"),
                    None => "-".to_string(),
                })
                .collect();
            for p in &e.points {
                let m = &p.measurement;
                let _ = writeln!(
                    out,
                    "{:<16} {:>6} {:>10.3} {:>10.4}  {:>10.4}  {:>10.4}   {}",
                    format!("{} {} spp", e.name, p.spp),
                    "-",
                    m.gpu_ms,
                    m.dssim,
                    m.flip,
                    m.rel_mse,
                    times.join(" / ")
                );
            }
        }
        out.push_str("* on the Pareto front of time per frame and final error\n");
        if !self.externals.is_empty() {
            out.push_str("external series: one image per line, ms/frame is that image's time\n");
        }
        out
    }
}

/// Per configuration, (ms per frame, final `metric`).
fn speed_accuracy(results: &[ConfigResult], metric: Metric) -> Vec<(f64, f64)> {
    results
        .iter()
        .map(|r| {
            (
                r.ms_per_frame(),
                r.last().map_or(f64::NAN, |row| metric.of(row)),
            )
        })
        .collect()
}

/// `error_vs_time_<metric>.png/.svg` (with the external series), `speed_vs_accuracy.png/.svg`
/// (Lucid's configurations: an external series has no time per frame) and
/// `time_to_converge.png/.svg` (both).
fn write_charts(
    out: &Path,
    results: &[ConfigResult],
    externals: &[ExternalResult],
    clock: Clock,
    target: impl Fn(Metric) -> f64,
) -> anyhow::Result<()> {
    let time = match clock {
        Clock::Gpu => "GPU time",
        Clock::Wall => "wall time",
    };
    for metric in Metric::ALL {
        let series: Vec<Series> = results
            .iter()
            .map(|r| Series {
                name: r.config.name(),
                points: measured_frames(&r.rows)
                    .map(|row| (row.gpu_ms, metric.of(row)))
                    .collect(),
            })
            .chain(externals.iter().map(|e| {
                Series {
                    name: e.label(),
                    points: e
                        .points
                        .iter()
                        .map(|p| (p.measurement.gpu_ms, metric.of(&p.measurement)))
                        .collect(),
                }
            }))
            .collect();
        let chart = converge_chart::error_vs_time(
            &format!("{} against {time}", metric.label()),
            &format!("{time} (ms, accumulated)"),
            metric.label(),
            target(metric),
            &series,
        )?;
        let name = format!("error_vs_time_{}", metric.name());
        write(&out.join(format!("{name}.png")), &chart.png)?;
        write(&out.join(format!("{name}.svg")), chart.svg.as_bytes())?;
    }
    let panels: Vec<converge_chart::Panel> = Metric::ALL
        .iter()
        .map(|&metric| {
            let points = speed_accuracy(results, metric);
            converge_chart::Panel {
                title: format!("final {} (red: Pareto front)", metric.label()),
                y_label: metric.label().to_string(),
                front: pareto_front(&points),
                points: results
                    .iter()
                    .zip(points)
                    .map(|(r, p)| (r.config.name(), p))
                    .collect(),
            }
        })
        .collect();
    let chart = converge_chart::speed_vs_accuracy(&format!("{time} per frame (ms)"), &panels)?;
    write(&out.join("speed_vs_accuracy.png"), &chart.png)?;
    write(&out.join("speed_vs_accuracy.svg"), chart.svg.as_bytes())?;
    let panels: Vec<converge_chart::ConvergePanel> = Metric::ALL
        .iter()
        .map(|&metric| converge_panel(results, externals, metric, target(metric), time))
        .collect();
    let chart = converge_chart::time_to_converge(&format!("{time} (ms, accumulated)"), &panels)?;
    write(&out.join("time_to_converge.png"), &chart.png)?;
    write(&out.join("time_to_converge.svg"), chart.svg.as_bytes())?;
    Ok(())
}

/// One row per measured frame: a frame that reached several targets of the time ladder has a
/// row for each, the same point on an error-against-time chart.
fn measured_frames(rows: &[Measurement]) -> impl Iterator<Item = &Measurement> {
    rows.iter()
        .enumerate()
        .filter(|(i, row)| *i == 0 || rows[i - 1].frame != row.frame)
        .map(|(_, row)| row)
}

/// The time-to-converge panel of `metric`: per configuration, then per external series, the
/// time it first measured an error below `target` and how long it ran.
fn converge_panel(
    results: &[ConfigResult],
    externals: &[ExternalResult],
    metric: Metric,
    target: f64,
    time: &str,
) -> converge_chart::ConvergePanel {
    let reached = |name: String, rows: &[Measurement], ran_ms: f64| converge_chart::Reached {
        name,
        ms: time_to_converge(rows, metric, target),
        ran_ms,
    };
    let own = results
        .iter()
        .map(|r| reached(r.config.name(), &r.rows, r.gpu_ms));
    let other = externals.iter().map(|e| {
        let rows = e.rows();
        let ran_ms = rows.iter().map(|row| row.gpu_ms).fold(0.0, f64::max);
        reached(e.label(), &rows, ran_ms)
    });
    converge_chart::ConvergePanel {
        title: format!("{time} to {} < {target}", metric.label()),
        entries: own.chain(other).collect(),
    }
}
