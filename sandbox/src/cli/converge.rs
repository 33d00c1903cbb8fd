//! `lucid converge`: error against GPU time as samples accumulate, for every configuration
//! (algorithm x denoiser x samples per pixel per frame) of one scene seen by a still camera,
//! against a many-sample reference; written as CSV, JSON and charts (`converge_chart.rs`).

use super::converge_chart::{self, Series};
use super::float_range::finite_f64;
use super::output_path;
use super::progress::Progress;
use super::render_options::{exposure, samples_per_pixel};
use super::scene_source;
use super::sequence::REFERENCE_SPP_PER_FRAME;
use super::size::Size;
use anyhow::Context as _;
use clap::{Args, ValueEnum};
use lucid_engine::atomic_write::write_atomic;
use lucid_engine::capture::{ImageData, PngEncoding, ToneCurve};
use lucid_engine::graph::RenderGraph;
use lucid_engine::metrics::evaluate_frame;
use lucid_engine::{Context, ContextDesc};
use lucid_passes::denoise::neural::{InferencePath, NetworkWeights};
use lucid_passes::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel, Settings};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

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
    /// wall time on a device without timestamp queries).
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
    /// Output folder: `converge.csv`, `converge.json`, `error_vs_time_<metric>.png/.svg` and
    /// `speed_vs_accuracy.png/.svg`.
    #[arg(long, default_value = "converge")]
    out: PathBuf,
    /// Print the JSON summary to stdout instead of the table.
    #[arg(long)]
    json: bool,
}

/// A comma-separated list given on the command line: not empty, no entry twice.
#[derive(Clone, Debug, PartialEq)]
pub struct List<T>(pub Vec<T>);

/// Parses a comma-separated list of `what`s, each by `parse`: an empty list, an empty entry or an
/// entry given twice is an error.
fn list<T: PartialEq>(
    what: &'static str,
    parse: impl Fn(&str) -> Result<T, String>,
) -> impl Fn(&str) -> Result<List<T>, String> {
    move |text| {
        let mut items = Vec::new();
        if text.trim().is_empty() {
            return Err(format!("the list is empty: give at least one {what}"));
        }
        for entry in text.split(',').map(str::trim) {
            if entry.is_empty() {
                return Err(format!("an empty {what} in {text:?}"));
            }
            let item = parse(entry)?;
            if items.contains(&item) {
                return Err(format!("{what} {entry:?} is listed twice"));
            }
            items.push(item);
        }
        Ok(List(items))
    }
}

/// Parses a list of a `clap::ValueEnum`'s names (any case).
fn value_list<T: ValueEnum + PartialEq + Clone + Send + Sync + 'static>(
    what: &'static str,
) -> impl Fn(&str) -> Result<List<T>, String> + Clone + Send + Sync + 'static {
    move |text| {
        list(what, |entry| {
            T::from_str(entry, true).map_err(|_| {
                let names: Vec<String> = T::value_variants()
                    .iter()
                    .filter_map(|v| v.to_possible_value())
                    .map(|v| v.get_name().to_string())
                    .collect();
                format!("unknown {what} {entry:?} (expected {})", names.join(", "))
            })
        })(text)
    }
}

/// Parses `--spp`: a list of sample counts from 1 to 65536.
fn spp_list() -> impl Fn(&str) -> Result<List<SamplesPerPixel>, String> + Clone + Send + Sync {
    move |text| {
        list("sample count", |entry| {
            entry
                .parse::<u32>()
                .ok()
                .filter(|n| (1..=65536).contains(n))
                .and_then(SamplesPerPixel::new)
                .ok_or_else(|| format!("{entry:?} is not a sample count from 1 to 65536"))
        })(text)
    }
}

/// The errors a configuration is measured by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metric {
    /// `1 / SSIM - 1` of the display-encoded images.
    Dssim,
    /// Mean LDR-FLIP of the tone-mapped images.
    Flip,
    /// Relative MSE of the linear images.
    RelMse,
}

impl Metric {
    /// Every metric, in the CSV's column order.
    pub const ALL: [Metric; 3] = [Metric::Dssim, Metric::Flip, Metric::RelMse];

    /// The name in the CSV, the JSON and file names.
    pub fn name(self) -> &'static str {
        match self {
            Metric::Dssim => "dssim",
            Metric::Flip => "flip",
            Metric::RelMse => "rel_mse",
        }
    }

    /// The name on charts.
    pub fn label(self) -> &'static str {
        match self {
            Metric::Dssim => "DSSIM",
            Metric::Flip => "FLIP",
            Metric::RelMse => "relMSE",
        }
    }

    /// This metric of a measurement.
    pub fn of(self, row: &Row) -> f64 {
        match self {
            Metric::Dssim => row.dssim,
            Metric::Flip => row.flip,
            Metric::RelMse => row.rel_mse,
        }
    }
}

/// One configuration: what renders each frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Config {
    /// The light transport.
    pub algorithm: Algorithm,
    /// The denoiser.
    pub denoiser: Denoiser,
    /// Samples per pixel per frame.
    pub spp: SamplesPerPixel,
}

impl Config {
    /// `ALGO/DENOISER/SPP`, as `--split` takes it (`pt/svgf/2`).
    pub fn name(&self) -> String {
        format!(
            "{}/{}/{}",
            self.algorithm.short_name(),
            self.denoiser.short_name(),
            self.spp
        )
    }
}

/// The error of a configuration's image after `frame` frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    /// Frames accumulated (1 for the first).
    pub frame: u32,
    /// GPU milliseconds of all frames up to and including this one (wall milliseconds on a device
    /// without timestamps: the JSON's `time` says which).
    pub gpu_ms: f64,
    /// `1 / SSIM - 1`.
    pub dssim: f64,
    /// Mean FLIP.
    pub flip: f64,
    /// Relative MSE.
    pub rel_mse: f64,
}

/// What one configuration did within its budget.
#[derive(Clone, Debug, PartialEq)]
pub struct ConfigResult {
    /// The configuration.
    pub config: Config,
    /// The measurements, at frames [`measured`] picks and at the last frame.
    pub rows: Vec<Row>,
    /// Frames rendered.
    pub frames: u32,
    /// GPU milliseconds of all frames.
    pub gpu_ms: f64,
}

impl ConfigResult {
    /// Mean GPU milliseconds per frame.
    pub fn ms_per_frame(&self) -> f64 {
        self.gpu_ms / f64::from(self.frames.max(1))
    }

    /// The last measurement (at the last frame).
    pub fn last(&self) -> Option<&Row> {
        self.rows.last()
    }
}

/// Whether the error is measured after `frame` frames (besides the last frame): geometrically
/// spaced frames 1, 2, 3, 4, 6, 8, 12, 16, 24, ... (powers of two and three times them), so a
/// long run costs few measurements.
pub fn measured(frame: u32) -> bool {
    frame.is_power_of_two() || (frame % 3 == 0 && (frame / 3).is_power_of_two())
}

/// The cumulative GPU time of the first row whose `metric` falls below `target`; `None` if none
/// does.
pub fn time_to_converge(rows: &[Row], metric: Metric, target: f64) -> Option<f64> {
    rows.iter()
        .find(|row| metric.of(row) < target)
        .map(|row| row.gpu_ms)
}

/// The Pareto front of `points` (time, error), both to be small: the indices of the points no
/// other point dominates (one at most as slow and at most as wrong, and better in one of the two),
/// by increasing time. Points with a non-finite coordinate are neither on the front nor dominate.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let finite = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite();
    let dominates =
        |q: (f64, f64), p: (f64, f64)| q.0 <= p.0 && q.1 <= p.1 && (q.0 < p.0 || q.1 < p.1);
    let mut front: Vec<usize> = (0..points.len())
        .filter(|&i| finite(&points[i]))
        .filter(|&i| {
            !points
                .iter()
                .filter(|q| finite(q))
                .any(|&q| dominates(q, points[i]))
        })
        .collect();
    front.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    front
}

/// How frame times are measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Clock {
    /// GPU timestamps around each pass, summed.
    Gpu,
    /// Wall time from submission to completion (devices without timestamp queries).
    Wall,
}

/// Runs the measurement and writes its files.
pub fn run(args: &ConvergeArgs) -> anyhow::Result<()> {
    output_path::create_folder("--out", &args.out)?;
    let weights = match &args.neural_weights {
        Some(path) => Some(NetworkWeights::load(path)?),
        None => None,
    };
    let scene = scene_source::load(&args.scene)?;
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
    let clock = if ctx.info().timestamps {
        Clock::Gpu
    } else {
        notes.push(format!(
            "{device} has no timestamp queries on its compute queue: times are wall times \
             (submission to completion), not GPU times"
        ));
        Clock::Wall
    };
    for note in &notes {
        eprintln!("note: {note}");
    }
    let configs: Vec<Config> = algorithms
        .iter()
        .flat_map(|&algorithm| {
            args.denoisers.0.iter().flat_map(move |&denoiser| {
                args.spp.0.iter().map(move |&spp| Config {
                    algorithm,
                    denoiser,
                    spp,
                })
            })
        })
        .collect();
    let (w, h) = (args.size.width, args.size.height);
    let display = PngEncoding {
        exposure: args.exposure,
        tone: ToneCurve::Aces,
    };
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
    let reference = render_reference(&mut renderer, base, args.reference_spp)?;
    anyhow::ensure!(
        !reference.has_non_finite(),
        "the reference has non-finite pixels"
    );
    eprintln!(
        "{} configurations, up to {} frames or {} ms each",
        configs.len(),
        args.max_frames,
        args.budget_ms
    );
    let progress = Progress::new(configs.len() as u64 * u64::from(args.max_frames), "frames");
    let mut results = Vec::new();
    for &config in &configs {
        let settings = Settings {
            algorithm: config.algorithm,
            denoiser: config.denoiser,
            samples_per_pixel: config.spp,
            ..base
        };
        let result = measure(&mut renderer, settings, &reference, args, clock, &progress)
            .with_context(|| format!("measuring {}", config.name()))?;
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
    };
    let json = summary.to_json();
    write(&args.out.join("converge.csv"), to_csv(&results).as_bytes())?;
    write(
        &args.out.join("converge.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    write_charts(&args.out, &results, clock, |m| summary.target(m))?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        print!("{}", summary.table());
        println!("-> {}", args.out.display());
    }
    Ok(())
}

/// Renders the reference: path tracing without a denoiser, `spp` samples per pixel accumulated
/// over frames of 16 (as `lucid sequence` makes its references), with another seed than the
/// configurations so its noise is independent of theirs.
fn render_reference(
    renderer: &mut Renderer,
    base: Settings,
    spp: SamplesPerPixel,
) -> anyhow::Result<ImageData> {
    renderer.set_settings(Settings {
        algorithm: Algorithm::PathTracing,
        denoiser: Denoiser::None,
        samples_per_pixel: spp.min(REFERENCE_SPP_PER_FRAME),
        seed: base.seed ^ 0x9e37_79b9,
        ..base
    });
    renderer.cut();
    let frames = spp.get().div_ceil(REFERENCE_SPP_PER_FRAME.get());
    eprintln!("reference: {} spp in {frames} frames", spp.get());
    let progress = Progress::new(u64::from(frames), "reference frames");
    for _ in 1..frames {
        renderer.render()?;
        progress.inc();
    }
    let image = renderer.render_and_read()?;
    progress.inc();
    progress.finish();
    Ok(image)
}

/// Renders `--warmup` frames of `settings`, then frames from a fresh start until the budget is spent or `--max-frames`
/// reached, measuring the error of the accumulated (and denoised) HDR image at the frames
/// [`measured`] picks and at the last.
fn measure(
    renderer: &mut Renderer,
    settings: Settings,
    reference: &ImageData,
    args: &ConvergeArgs,
    clock: Clock,
    progress: &Progress,
) -> anyhow::Result<ConfigResult> {
    renderer.set_settings(settings);
    for _ in 0..args.warmup {
        renderer.render()?;
    }
    renderer.finish()?;
    renderer.cut();
    let mut rows = Vec::new();
    let mut gpu_ms = 0.0;
    let mut frames = 0;
    for frame in 1..=args.max_frames {
        let mut g = RenderGraph::new();
        let (images, stats) = renderer.add_frame(&mut g);
        // The displayed image leaves the graph as in `lucid bench` (its passes are part of a
        // frame); the HDR image is what is measured.
        g.readback(images.ldr);
        let hdr = g.readback(images.hdr);
        let started = Instant::now();
        let submitted = renderer.executor_mut().execute(g.compile()?)?;
        let outputs = renderer.executor_mut().wait(submitted)?;
        let wall_ms = started.elapsed().as_secs_f64() * 1e3;
        renderer.collect_stats(&outputs, stats)?;
        gpu_ms += match clock {
            // Pass times summed as `lucid bench` sums them, less the copies to the host, which
            // here serve only the measurement.
            Clock::Gpu => outputs
                .timings
                .iter()
                .filter(|t| !t.name.starts_with("readback"))
                .map(|t| t.ms)
                .sum::<f64>(),
            Clock::Wall => wall_ms,
        };
        frames = frame;
        let last = frame == args.max_frames || gpu_ms >= args.budget_ms;
        if measured(frame) || last {
            let image = outputs.image(hdr)?;
            let display = settings.display;
            let m = evaluate_frame(&image, reference, &display)?;
            rows.push(Row {
                frame,
                gpu_ms,
                dssim: m.dssim,
                flip: m.flip,
                rel_mse: m.rel_mse,
            });
        }
        progress.inc();
        if last {
            break;
        }
    }
    progress.inc_by(u64::from(args.max_frames - frames));
    renderer.finish()?;
    Ok(ConfigResult {
        config: Config {
            algorithm: settings.algorithm,
            denoiser: settings.denoiser,
            spp: settings.samples_per_pixel,
        },
        rows,
        frames,
        gpu_ms,
    })
}

fn write(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    write_atomic(path, bytes).with_context(|| format!("writing {}", path.display()))
}

/// The CSV's header.
pub const CSV_HEADER: &str = "config,algo,denoiser,spp,frame,gpu_ms,dssim,flip,rel_mse";

/// One line per measurement; numbers in full precision (what the JSON's times to converge are
/// computed from).
fn to_csv(results: &[ConfigResult]) -> String {
    let mut out = format!("{CSV_HEADER}\n");
    for r in results {
        let c = r.config;
        for row in &r.rows {
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{}",
                c.name(),
                c.algorithm.short_name(),
                c.denoiser.short_name(),
                c.spp,
                row.frame,
                row.gpu_ms,
                row.dssim,
                row.flip,
                row.rel_mse
            );
        }
    }
    out
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
                        "gpu_ms": row.gpu_ms,
                        "dssim": row.dssim,
                        "flip": row.flip,
                        "rel_mse": row.rel_mse,
                    })).collect::<Vec<_>>(),
                })
            })
            .collect();
        let args = self.args;
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
            "reference_spp": args.reference_spp.get(),
            "budget_ms": args.budget_ms,
            "max_frames": args.max_frames,
            "warmup": args.warmup,
            "reference": "path tracing, no denoiser, seed xor 0x9e3779b9, 16 samples per frame accumulated",
            "time": time,
            "exposure": args.exposure,
            "notes": self.notes,
            "targets": per_metric(&|m| json!(self.target(m))),
            "pareto_front": per_metric(&|m| {
                let (_, front) = fronts.iter().find(|(f, _)| *f == m).expect("every metric");
                json!(front.iter().map(|&i| self.results[i].config.name()).collect::<Vec<_>>())
            }),
            "configurations": configurations,
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
        out.push_str("* on the Pareto front of time per frame and final error\n");
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

/// `error_vs_time_<metric>.png/.svg` and `speed_vs_accuracy.png/.svg`.
fn write_charts(
    out: &Path,
    results: &[ConfigResult],
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
                points: r
                    .rows
                    .iter()
                    .map(|row| (row.gpu_ms, metric.of(row)))
                    .collect(),
            })
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
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pareto_front_is_the_points_nothing_beats_in_both() {
        // (ms per frame, error)
        let points = [
            (1.0, 0.50),     // 0: fastest: on the front
            (2.0, 0.20),     // 1: on the front
            (2.5, 0.30),     // 2: dominated by 1 (slower and worse)
            (4.0, 0.05),     // 3: most accurate: on the front
            (4.0, 0.06),     // 4: as slow as 3 and worse: dominated
            (2.0, 0.20),     // 5: equal to 1: neither dominates the other
            (0.5, f64::NAN), // 6: no error: not on the front, dominates nothing
            (8.0, 0.05),     // 7: as accurate as 3, slower: dominated
        ];
        assert_eq!(pareto_front(&points), vec![0, 1, 5, 3]);
        assert_eq!(pareto_front(&[]), Vec::<usize>::new());
        assert_eq!(pareto_front(&[(3.0, 0.1)]), vec![0]);
    }

    #[test]
    fn errors_are_measured_at_geometrically_spaced_frames() {
        let frames: Vec<u32> = (1..=50).filter(|&f| measured(f)).collect();
        assert_eq!(frames, [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48]);
    }

    #[test]
    fn time_to_converge_is_the_first_time_below_the_target() {
        let row = |frame, gpu_ms, dssim| Row {
            frame,
            gpu_ms,
            dssim,
            flip: 0.5,
            rel_mse: 0.5,
        };
        let rows = [
            row(1, 2.0, 0.3),
            row(2, 4.0, 0.09),
            row(3, 6.0, 0.12),
            row(4, 8.0, 0.05),
        ];
        assert_eq!(time_to_converge(&rows, Metric::Dssim, 0.1), Some(4.0));
        assert_eq!(time_to_converge(&rows, Metric::Dssim, 0.09), Some(8.0));
        assert_eq!(time_to_converge(&rows, Metric::Flip, 0.1), None);
    }

    #[test]
    fn lists_are_checked() {
        let algos = value_list::<Algorithm>("algorithm");
        assert_eq!(
            algos("pt, BDPT"),
            Ok(List(vec![Algorithm::PathTracing, Algorithm::Bidirectional]))
        );
        assert_eq!(
            algos("pt,mlt").unwrap_err(),
            "unknown algorithm \"mlt\" (expected pt, bdpt)"
        );
        assert!(algos("").unwrap_err().contains("empty"));
        assert!(algos("pt,,bdpt").unwrap_err().contains("empty"));
        assert!(algos("pt,pt").unwrap_err().contains("twice"));
        let spp = spp_list();
        assert_eq!(
            spp("1,4")
                .unwrap()
                .0
                .iter()
                .map(|s| s.get())
                .collect::<Vec<_>>(),
            [1, 4]
        );
        for bad in ["0", "1,0", "-1", "x", "65537"] {
            assert!(spp(bad).is_err(), "{bad}");
        }
        let denoisers = value_list::<Denoiser>("denoiser");
        assert!(denoisers("none,oidn")
            .unwrap_err()
            .contains("none, svgf, neural"));
    }
}
