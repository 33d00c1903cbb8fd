//! `lucid sequence`: renders a scene's camera path as a reference and through each denoiser, then
//! evaluates them (`lucid evaluate`).

use super::auto_options::AlgoArg;
use super::evaluate;
use super::float_range::finite_f32;
use super::output_path;
use super::progress::Progress;
use super::render_options::{samples_per_pixel, RenderOptions};
use super::scene_source;
use super::stability;
use anyhow::Context as _;
use clap::Args;
use lucid_engine::capture::{self, ExrPrecision, ImageData};
use lucid_engine::scene::{Camera, Scene};
use lucid_engine::{Context, ContextDesc};
use lucid_passes::denoise::neural::{
    record_image, InferencePath, NetworkWeights, RECORD_ALBEDO, RECORD_NORMAL,
};
use lucid_passes::denoise::svgf::{SvgfMode, SvgfParams};
use lucid_passes::renderer::{Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_passes::tradeoff::measure::REFERENCE_SPP_PER_FRAME;
use std::path::{Path, PathBuf};

/// Options of `lucid sequence`.
#[derive(Debug, Args)]
pub struct SequenceArgs {
    #[command(flatten)]
    options: RenderOptions,
    /// Frames of the camera path to render.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(2..))]
    frames: u32,
    /// Frames per second along the camera path.
    #[arg(long, default_value_t = 30.0, value_parser = finite_f32(0.01, 1000.0))]
    fps: f32,
    /// Samples per pixel of each reference frame.
    #[arg(long, default_value = "1024", value_parser = samples_per_pixel(u32::MAX.into()))]
    reference_spp: SamplesPerPixel,
    /// Output folder: `<method>/NNNN.exr` frames and `<method>/gpu_ms.txt` (the GPU time of each
    /// frame, the path rendered again back to back), first-hit `albedo/` and `normal/` frames, `metrics.csv`, `metrics.svg` and the
    /// stability chart `stability.svg`/`.png`.
    #[arg(long, default_value = "sequence")]
    out: PathBuf,
    /// Only render; evaluate later with `lucid evaluate` (e.g. after adding an `oidn/` folder).
    #[arg(long)]
    no_evaluate: bool,
    /// More learned-denoiser weights (files `training/train.py` wrote), each rendered and evaluated
    /// as one more method, `neural-<file stem>/`, beside `neural/` (the committed weights, or
    /// `--neural-weights`).
    #[arg(long, value_name = "FILE")]
    also_neural_weights: Vec<PathBuf>,
    /// Also render the reference again with another seed, into `second-reference/`, evaluated as
    /// one more method: its error against `reference/` is the reference's own noise, a floor under
    /// what any method can measure against it.
    #[arg(long)]
    second_reference: bool,
    /// Also render the reference with this many samples per pixel (more than
    /// `--reference-spp`) and yet another seed, into `converged-reference/`, evaluated as one more
    /// method: what an exact method would measure against `reference/`. Where a method measures
    /// better than this, its figures no longer rank closeness to the truth.
    #[arg(long, value_name = "SPP", value_parser = samples_per_pixel(u32::MAX.into()))]
    converged_reference_spp: Option<SamplesPerPixel>,
}

/// The folder and method name of the reference rendered again with another seed
/// (`--second-reference`).
pub const SECOND_REFERENCE: &str = "second-reference";

/// The folder and method name of the reference rendered with more samples and another seed
/// (`--converged-reference-spp`).
pub const CONVERGED_REFERENCE: &str = "converged-reference";

/// The method name of learned-denoiser weights given with `--also-neural-weights`.
pub fn extra_neural_method(weights: &Path) -> String {
    let stem = weights
        .file_stem()
        .map_or_else(|| "weights".into(), |s| s.to_string_lossy());
    format!("{}-{stem}", Denoiser::Neural.short_name())
}

/// The sequences rendered besides the reference: the noisy input and each denoiser, at `--spp`
/// samples per pixel (1 by default).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// No denoiser.
    Noisy,
    /// SVGF's spatial filter on every frame, without history.
    Spatial,
    /// Temporal SVGF.
    Svgf,
    /// The learned recurrent denoiser.
    Neural,
}

impl Method {
    /// Every method, in the order they are rendered and evaluated.
    pub const ALL: [Method; 4] = [Method::Noisy, Method::Spatial, Method::Svgf, Method::Neural];

    /// The method's folder and its name in the metrics (`none`, `spatial`, `svgf`, `neural`).
    pub fn name(self) -> &'static str {
        match self {
            Method::Noisy => Denoiser::None.short_name(),
            Method::Spatial => "spatial",
            Method::Svgf => Denoiser::Svgf.short_name(),
            Method::Neural => Denoiser::Neural.short_name(),
        }
    }

    /// `base` with this method's denoiser.
    fn settings(self, base: Settings) -> Settings {
        let svgf = |mode| SvgfParams { mode, ..base.svgf };
        match self {
            Method::Noisy => Settings {
                denoiser: Denoiser::None,
                ..base
            },
            Method::Spatial => Settings {
                denoiser: Denoiser::Svgf,
                svgf: svgf(SvgfMode::EveryFrame),
                ..base
            },
            Method::Svgf => Settings {
                denoiser: Denoiser::Svgf,
                svgf: svgf(SvgfMode::Temporal),
                ..base
            },
            Method::Neural => Settings {
                denoiser: Denoiser::Neural,
                ..base
            },
        }
    }
}

/// Renders every sequence and writes the evaluation.
pub fn run(args: &SequenceArgs) -> anyhow::Result<()> {
    if let Some(spp) = args.converged_reference_spp {
        anyhow::ensure!(
            spp > args.reference_spp,
            "--converged-reference-spp {spp} must exceed --reference-spp {}",
            args.reference_spp
        );
    }
    output_path::create_folder("--out", &args.out)?;
    let scene = scene_source::load(&args.options.scene, args.options.env.as_deref())?;
    let path = scene
        .camera_path
        .clone()
        .with_context(|| format!("scene {} has no camera path", scene.name))?;
    let cameras: Vec<Camera> = (0..args.frames)
        .map(|i| path.sample(i as f32 / args.fps))
        .collect();
    let ctx = Context::new(&ContextDesc::from_env())?;
    let base = sequence_settings(&ctx, &scene, args, cameras[0])?;
    // The references: `spp` samples a pixel as frames of at most REFERENCE_SPP_PER_FRAME
    // accumulated per camera, with `seed_offset` added to the path's seed.
    let reference = |name: &str, spp: SamplesPerPixel, seed_offset: u32| {
        let settings = Settings {
            samples_per_pixel: spp.min(REFERENCE_SPP_PER_FRAME),
            accumulate: true,
            denoiser: Denoiser::None,
            seed: base.seed.wrapping_add(seed_offset),
            ..base
        };
        let frames = spp.get().div_ceil(REFERENCE_SPP_PER_FRAME.get());
        render(&ctx, &scene, args, &cameras, name, settings, frames)
    };
    reference("reference", args.reference_spp, 0)?;
    if args.second_reference {
        reference(SECOND_REFERENCE, args.reference_spp, 1)?;
    }
    if let Some(spp) = args.converged_reference_spp {
        reference(CONVERGED_REFERENCE, spp, 2)?;
    }
    let extra: Vec<(String, NetworkWeights)> = args
        .also_neural_weights
        .iter()
        .map(|path| Ok((extra_neural_method(path), NetworkWeights::load(path)?)))
        .collect::<anyhow::Result<_>>()?;
    for method in Method::ALL {
        let settings = method.settings(base);
        render(&ctx, &scene, args, &cameras, method.name(), settings, 1)?;
    }
    for (name, weights) in &extra {
        let settings = Method::Neural.settings(base);
        let network = Some((weights, args.options.neural_path));
        render_with(&ctx, &scene, args, &cameras, (name, settings), network)?;
    }
    if args.no_evaluate {
        return Ok(());
    }
    evaluate::evaluate_folder(&args.out, &args.options.display(), false, None)
}

/// The settings every method starts from: the options', or with `--algo auto` the algorithm and
/// samples per pixel a calibration from the path's first camera picks (each method keeps its own
/// denoiser).
fn sequence_settings(
    ctx: &Context,
    scene: &Scene,
    args: &SequenceArgs,
    first: Camera,
) -> anyhow::Result<Settings> {
    let options = &args.options;
    let base = options.settings(false);
    if options.algo != AlgoArg::Auto {
        options.auto.check(options.algo)?;
        return Ok(base);
    }
    let (w, h) = (options.size.width, options.size.height);
    let mut renderer = options.renderer(ctx, scene.clone(), (w, h), base)?;
    renderer.set_camera(first);
    let choice = options
        .auto
        .calibrate(&mut renderer, options.denoise, options.spp)?;
    eprintln!(
        "auto: every method renders with {} at {} spp",
        choice.config.algorithm.label(),
        choice.config.spp
    );
    Ok(Settings {
        algorithm: choice.config.algorithm,
        samples_per_pixel: choice.config.spp,
        ..base
    })
}

/// Renders `cameras` with `settings`, accumulating `frames_each` frames per camera, into
/// `<out>/<name>/NNNN.exr` (and, for a method rendered one frame a camera, the GPU time of each
/// frame of the path rendered back to back into `<out>/<name>/gpu_ms.txt`: [`time_path`]). With the learned denoiser, also each frame's first-hit albedo and
/// normal from its record (`albedo/NNNN.exr`, `normal/NNNN.exr`), which image denoisers run per
/// frame take besides the noisy radiance (`training/oidn_baseline.py`).
fn render(
    ctx: &Context,
    scene: &Scene,
    args: &SequenceArgs,
    cameras: &[Camera],
    name: &str,
    settings: Settings,
    frames_each: u32,
) -> anyhow::Result<()> {
    let (w, h) = (args.options.size.width, args.options.size.height);
    let renderer = args
        .options
        .renderer(ctx, scene.clone(), (w, h), settings)?;
    render_frames(renderer, args, cameras, name, frames_each)
}

/// Renders `cameras` with the learned denoiser as [`render`] does, with `network`'s weights (on
/// its inference path, or the device's best) into `<out>/<name>/`.
fn render_with(
    ctx: &Context,
    scene: &Scene,
    args: &SequenceArgs,
    cameras: &[Camera],
    (name, settings): (&str, Settings),
    network: Option<(&NetworkWeights, Option<InferencePath>)>,
) -> anyhow::Result<()> {
    let (w, h) = (args.options.size.width, args.options.size.height);
    let mut renderer = Renderer::new(ctx, scene.clone(), w, h, settings)?;
    if let Some((weights, path)) = network {
        renderer.set_neural_network(weights, path.unwrap_or(InferencePath::best(ctx)))?;
    }
    render_frames(renderer, args, cameras, name, 1)
}

/// [`render`]'s frames, by `renderer`.
fn render_frames(
    mut renderer: Renderer,
    args: &SequenceArgs,
    cameras: &[Camera],
    name: &str,
    frames_each: u32,
) -> anyhow::Result<()> {
    let (w, h) = (args.options.size.width, args.options.size.height);
    let neural = renderer.settings().denoiser == Denoiser::Neural;
    let folder = args.out.join(name);
    std::fs::create_dir_all(&folder).with_context(|| format!("creating {}", folder.display()))?;
    eprintln!("{name}: {} frames", cameras.len());
    let aux = if neural {
        [("albedo", RECORD_ALBEDO), ("normal", RECORD_NORMAL)].as_slice()
    } else {
        &[]
    };
    for (name, _) in aux {
        let folder = args.out.join(name);
        std::fs::create_dir_all(&folder)
            .with_context(|| format!("creating {}", folder.display()))?;
    }
    let progress = Progress::new(cameras.len() as u64, "frames");
    for (i, &camera) in cameras.iter().enumerate() {
        renderer.set_camera(camera);
        for _ in 1..frames_each {
            renderer.render()?;
        }
        let image = if aux.is_empty() {
            renderer.render_and_read()?
        } else {
            let (image, record) = renderer.render_and_read_record()?;
            for &(name, channel) in aux {
                let first_hit = record_image(&record, (w, h), channel)?;
                save(&frame_path(&args.out.join(name), i), &first_hit)?;
            }
            image
        };
        save(&frame_path(&folder, i), &image)?;
        progress.inc();
    }
    progress.finish();
    if frames_each == 1 {
        stability::write_gpu_times(&folder, &time_path(&mut renderer, cameras)?)?;
    }
    renderer.finish()?;
    Ok(())
}

/// The GPU time of each frame of the camera path rendered again, back to back and saving nothing,
/// after the path once as a warm-up: between the saved frames the GPU waits for the files to be
/// written, and an idle GPU lowers its clocks (on an H100 the path's saved frames took up to 5x
/// a bench's time), so their times are not a game loop's. The frames are not kept.
fn time_path(renderer: &mut Renderer, cameras: &[Camera]) -> anyhow::Result<Vec<f64>> {
    let mut times = Vec::with_capacity(cameras.len());
    for round in 0..2 {
        for &camera in cameras {
            renderer.set_camera(camera);
            renderer.render()?;
            if round == 1 {
                // The stats are those of the frame before, which this one waited for.
                times.push(renderer.stats().gpu_ms);
            }
        }
    }
    renderer.finish()?;
    times.push(renderer.stats().gpu_ms);
    // The first is the warm-up's last frame.
    times.remove(0);
    Ok(times)
}

/// The file of frame `index` in a method's folder.
pub fn frame_path(folder: &Path, index: usize) -> PathBuf {
    folder.join(format!("{index:04}.exr"))
}

fn save(path: &Path, image: &ImageData) -> anyhow::Result<()> {
    capture::save_exr(path, image, ExrPrecision::F32)
        .with_context(|| format!("writing {}", path.display()))
}
