//! `lucid view` (and `lucid` without a subcommand): the interactive sandbox window.

use super::auto_options::AlgoArg;
use super::render_options::{bdpt_connections, connection_roulette, samples_per_pixel};
use super::size::Size;
use super::split::SplitSpec;
use anyhow::Context as _;
use clap::Args;
use lucid_passes::denoise::neural::NeuralParams;
use lucid_passes::light_transport::bdpt::{MisHeuristic, DEFAULT_CONNECTION_ROULETTE};
use lucid_sandbox::{
    Algorithm, AppOptions, Denoiser, EdgeEmission, RenderSettings, SamplesPerPixel, Screenshot,
    Startup, DEFAULT_SCENE,
};
use std::num::NonZeroU32;
use std::path::PathBuf;

/// Options of `lucid view` (and of `lucid` without a subcommand).
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// A built-in scene name (see `lucid render --help`) or a `.gltf` / `.glb` file.
    #[arg(default_value = DEFAULT_SCENE)]
    scene: String,
    /// An equirectangular environment map (.hdr or .exr, twice as wide as high) lighting the
    /// scene in place of its environment, importance sampled.
    #[arg(long, value_name = "FILE")]
    env: Option<PathBuf>,
    /// Initial window size.
    #[arg(long, default_value = "1280x720")]
    size: Size,
    /// Directory F12 captures are written to.
    #[arg(long, default_value = ".")]
    capture_dir: PathBuf,
    /// After N frames, save the window (UI included) as a PNG and exit.
    #[arg(long, num_args = 2, value_names = ["N", "FILE"])]
    screenshot_after: Option<Vec<String>>,
    /// Light-transport algorithm (of the left half in a split view), or `auto`: calibrate on the
    /// scene at the window's size before the first frame and pick algorithm, denoiser and samples
    /// per pixel for 60 frames per second (the panel's "Auto configuration" re-runs it).
    #[arg(long, value_enum, default_value = "pt")]
    algo: AlgoArg,
    /// Denoiser (of the left half in a split view).
    #[arg(long, value_enum, default_value_t = Denoiser::Svgf)]
    denoise: Denoiser,
    /// Supersample the emission the denoisers add back at emitters' edges (also a panel choice).
    /// `auto`: for the learned denoiser, not for SVGF; the option alone means `on`.
    #[arg(long, value_enum, value_name = "WHEN", default_value_t = EdgeEmission::ByDenoiser,
          num_args = 0..=1, default_missing_value = "on")]
    edge_emission: EdgeEmission,
    /// The learned denoiser's gated filter over its output, `on` or `off` (also a panel choice).
    #[arg(long, value_name = "on|off", default_value = "on", action = clap::ArgAction::Set,
          value_parser = clap::builder::BoolishValueParser::new())]
    neural_filter: bool,
    /// Samples per pixel per frame.
    #[arg(long, default_value_t = SamplesPerPixel::ONE, value_parser = samples_per_pixel(1024))]
    spp: SamplesPerPixel,
    /// Longest path.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=64))]
    max_depth: u32,
    /// Cached light vertices each BDPT camera vertex connects to (also a panel choice).
    #[arg(long, default_value_t = NonZeroU32::MIN,
          value_parser = bdpt_connections())]
    bdpt_connections: NonZeroU32,
    /// How BDPT's multiple importance sampling weighs its strategies (also a panel choice).
    #[arg(long, value_enum, default_value_t = MisHeuristic::Power)]
    bdpt_mis: MisHeuristic,
    /// BDPT's connection roulette, a share of what a camera subpath has gathered (and light
    /// tracing's MIS weight, up to 1); 0 off (also a panel setting).
    #[arg(long, default_value_t = DEFAULT_CONNECTION_ROULETTE, value_name = "SHARE",
          value_parser = connection_roulette())]
    bdpt_connection_roulette: f32,
    /// Start in the split view: the right half renders ALGO/DENOISER[/SPP[/DEPTH]] (e.g.
    /// `bdpt/none`), the left half the options above, both from the same camera.
    #[arg(long, value_name = "ALGO/DENOISER[/SPP[/DEPTH]]")]
    split: Option<SplitSpec>,
    /// Self-test of the window code: over the first frames, shrink the window, report it minimized,
    /// restore it and report its surface lost, printing each step (use with --screenshot-after 14
    /// or more).
    #[arg(long)]
    window_test: bool,
}

/// Opens the window.
pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    let screenshot = match args.screenshot_after.as_deref() {
        Some([frames, file]) => Some(Screenshot {
            after_frames: frames
                .parse()
                .ok()
                .filter(|&n: &u64| n > 0)
                .with_context(|| format!("--screenshot-after: {frames:?} is not a frame count"))?,
            path: PathBuf::from(file),
        }),
        _ => None,
    };
    let render = RenderSettings {
        algorithm: match args.algo {
            AlgoArg::Fixed(algorithm) => algorithm,
            AlgoArg::Auto => Algorithm::PathTracing,
        },
        denoiser: args.denoise,
        edge_emission: args.edge_emission,
        neural: NeuralParams {
            gated_filter: args.neural_filter,
        },
        spp: args.spp,
        max_depth: args.max_depth,
        bdpt_connections: args.bdpt_connections,
        bdpt_mis: args.bdpt_mis,
        bdpt_connection_roulette: args.bdpt_connection_roulette,
        ..RenderSettings::default()
    };
    let options = AppOptions {
        scene: args.scene.clone(),
        env: args.env.clone(),
        size: [args.size.width, args.size.height],
        capture_dir: args.capture_dir.clone(),
        screenshot,
    };
    let startup = Startup {
        render,
        split: args.split.map(|spec| spec.apply(&render)),
        window_test: args.window_test,
        calibrate: args.algo == AlgoArg::Auto,
    };
    lucid_sandbox::run_with(options, startup)
}
