//! Options shared by `render`, `bench` and `sequence`: scene, algorithm (or `auto`), samples,
//! depth, size, seed, display.

use super::auto_options::{AlgoArg, AutoOptions};
use super::float_range::finite_f32;
use super::size::Size;
use clap::builder::TypedValueParser;
use clap::Args;
use lucid_engine::capture::{PngEncoding, ToneCurve};
use lucid_engine::scene::gpu::BvhLayout;
use lucid_engine::scene::Scene;
use lucid_engine::Context;
use lucid_passes::denoise::neural::{InferencePath, NetworkWeights, NeuralParams};
use lucid_passes::denoise::svgf::SvgfParams;
use lucid_passes::light_transport::bdpt::{MisHeuristic, DEFAULT_CONNECTION_ROULETTE};
use lucid_passes::renderer::{
    Algorithm, Denoiser, EdgeEmission, Renderer, SamplesPerPixel, Settings,
};
use std::num::NonZeroU32;
use std::path::PathBuf;

/// What to render and how.
#[derive(Debug, Args)]
pub struct RenderOptions {
    /// A built-in scene (see `lucid scenes`) or a .gltf/.glb file.
    #[arg(long, default_value = "cornell-box")]
    pub scene: String,
    /// An equirectangular environment map (.hdr or .exr, twice as wide as high) lighting the
    /// scene in place of its environment, importance sampled.
    #[arg(long, value_name = "FILE")]
    pub env: Option<PathBuf>,
    /// Light-transport algorithm, or `auto`: a short calibration on the scene picks algorithm,
    /// denoiser and samples per pixel for --quality or --budget-ms.
    #[arg(long, value_enum, default_value = "pt")]
    pub algo: AlgoArg,
    /// Samples per pixel per frame [default: 1; with --algo auto: chosen among 1, 2 and 4 unless
    /// given].
    #[arg(long, value_parser = samples_per_pixel(65536))]
    pub spp: Option<SamplesPerPixel>,
    /// Longest path (Mitsuba's convention: 1 = emitters only, 2 = direct light, ...).
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub max_depth: u32,
    /// Cached light vertices each BDPT camera vertex connects to (more: slower, less noise where
    /// light arrives through connections).
    #[arg(long, default_value_t = NonZeroU32::MIN,
          value_parser = bdpt_connections())]
    pub bdpt_connections: NonZeroU32,
    /// How BDPT's multiple importance sampling weighs its strategies.
    #[arg(long, value_enum, default_value_t = MisHeuristic::Power)]
    pub bdpt_mis: MisHeuristic,
    /// BDPT's connection roulette: a connection that would add less than this share of what its
    /// camera subpath has gathered, or a light-tracing one whose MIS weight is under it (at most
    /// 1), is traced with probability in proportion (unbiased: fewer shadow rays, a little more
    /// noise); 0 traces every connection.
    #[arg(long, default_value_t = DEFAULT_CONNECTION_ROULETTE, value_name = "SHARE",
          value_parser = connection_roulette())]
    pub bdpt_connection_roulette: f32,
    /// Image size.
    #[arg(long, default_value = "512x512")]
    pub size: Size,
    /// Seed of the random numbers.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Exposure in stops.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = exposure())]
    pub exposure: f32,
    /// Tone curve for PNG output and display.
    #[arg(long, value_enum, default_value_t = ToneCurve::Aces)]
    pub tone: ToneCurve,
    /// Denoiser applied after tracing [default: none; with --algo auto: chosen among all unless
    /// given].
    #[arg(long, value_enum)]
    pub denoise: Option<Denoiser>,
    /// Weights of the learned denoiser (a file `training/train.py` wrote) instead of the
    /// committed ones.
    #[arg(long)]
    pub neural_weights: Option<PathBuf>,
    /// How the learned denoiser's convolutions run (default: tensor cores where the device has
    /// them, else portable).
    #[arg(long, value_enum)]
    pub neural_path: Option<InferencePath>,
    /// Supersample the emission the denoiser adds back where an emitter's edge crosses a pixel (a
    /// 4x4 grid of camera rays there): steadier lights and windows under camera motion. `auto`:
    /// for the learned denoiser, not for SVGF; the option alone means `on`.
    #[arg(long, value_enum, value_name = "WHEN", default_value_t = EdgeEmission::ByDenoiser,
          num_args = 0..=1, default_missing_value = "on")]
    pub edge_emission: EdgeEmission,
    /// SVGF's firefly clamp (`on` or `off`): a sample may not raise the accumulated colour far
    /// above the history and samples around it. Off, a rare caustic path stays a bright spot for
    /// frames, but no light is lost.
    #[arg(long, value_name = "on|off", default_value = "on", action = clap::ArgAction::Set,
          value_parser = clap::builder::BoolishValueParser::new())]
    pub svgf_firefly_clamp: bool,
    /// How many times brighter than its neighbours (in SVGF's history and in the frame) the
    /// firefly clamp lets a sample be.
    #[arg(long, value_name = "RATIO", default_value_t = SvgfParams::default().firefly_headroom,
          value_parser = finite_f32(1.0, 1e6))]
    pub svgf_firefly_headroom: f32,
    /// The learned denoiser's gated a-trous filter over its output (`on` or `off`; the committed
    /// weights have one): off, the first frames after a cut are filtered less, for 0.20 ms less at
    /// 1080p on an H200.
    #[arg(long, value_name = "on|off", default_value = "on", action = clap::ArgAction::Set,
          value_parser = clap::builder::BoolishValueParser::new())]
    pub neural_filter: bool,
    /// Layout of the BVH nodes on the GPU (both find the same hits; for A/B timing). Default: wide
    /// for path tracing a scene small enough to walk in workgroup memory (the Cornell box), binary
    /// otherwise.
    #[arg(long, value_enum)]
    pub bvh: Option<BvhLayout>,
    #[command(flatten)]
    pub auto: AutoOptions,
}

impl RenderOptions {
    /// The renderer settings these options describe (with `--algo auto`, before the calibration
    /// replaces algorithm, denoiser and samples per pixel: path tracing, and the defaults of the
    /// ones not given).
    pub fn settings(&self, accumulate: bool) -> Settings {
        Settings {
            algorithm: match self.algo {
                AlgoArg::Fixed(algorithm) => algorithm,
                AlgoArg::Auto => Algorithm::PathTracing,
            },
            samples_per_pixel: self.spp.unwrap_or(SamplesPerPixel::ONE),
            max_depth: self.max_depth,
            bdpt_connections: self.bdpt_connections,
            bdpt_mis: self.bdpt_mis,
            bdpt_connection_roulette: self.bdpt_connection_roulette,
            seed: self.seed,
            accumulate,
            display: self.display(),
            denoiser: self.denoise.unwrap_or(Denoiser::None),
            edge_emission: self.edge_emission,
            svgf: SvgfParams {
                firefly_clamp: self.svgf_firefly_clamp,
                firefly_headroom: self.svgf_firefly_headroom,
                ..SvgfParams::default()
            },
            neural: NeuralParams {
                gated_filter: self.neural_filter,
            },
            ..Settings::default()
        }
    }

    /// A renderer of `scene` at `width` x `height` with `settings` as [`RenderOptions::renderer`]
    /// makes it; with `--algo auto`, then calibrated and switched to the configuration chosen
    /// (printed with the reason to stderr).
    pub fn calibrated_renderer(
        &self,
        ctx: &Context,
        scene: Scene,
        size: (u32, u32),
        settings: Settings,
    ) -> anyhow::Result<Renderer> {
        self.auto.check(self.algo)?;
        let mut renderer = self.renderer(ctx, scene, size, settings)?;
        if self.algo == AlgoArg::Auto {
            self.auto.calibrate(&mut renderer, self.denoise, self.spp)?;
        }
        Ok(renderer)
    }

    /// A renderer of `scene` at `width` x `height` with `settings`, the BVH layout and, when given,
    /// the learned denoiser's weights (a missing or malformed file is an error before anything
    /// renders).
    pub fn renderer(
        &self,
        ctx: &Context,
        scene: Scene,
        (width, height): (u32, u32),
        settings: Settings,
    ) -> anyhow::Result<Renderer> {
        let mut renderer = Renderer::new(ctx, scene, width, height, settings)?;
        renderer.set_bvh_layout(self.bvh)?;
        if self.neural_weights.is_some() || self.neural_path.is_some() {
            let weights = match &self.neural_weights {
                Some(path) => NetworkWeights::load(path)?,
                None => NetworkWeights::builtin(),
            };
            let path = self.neural_path.unwrap_or(InferencePath::best(ctx));
            renderer.set_neural_network(&weights, path)?;
        }
        Ok(renderer)
    }

    /// Exposure and tone curve.
    pub fn display(&self) -> PngEncoding {
        PngEncoding {
            exposure: self.exposure,
            tone: self.tone,
        }
    }
}

/// Parses `--spp`: a sample count from 1 to `max` (the one place a command line checks it).
pub fn samples_per_pixel(max: i64) -> impl TypedValueParser<Value = SamplesPerPixel> {
    clap::value_parser!(u32)
        .range(1..=max)
        .try_map(SamplesPerPixel::try_from)
}

/// Parses `--bdpt-connections`: 1 to 16 cached light vertices a camera vertex.
pub fn bdpt_connections() -> impl TypedValueParser<Value = NonZeroU32> {
    clap::value_parser!(u32)
        .range(1..=16)
        .try_map(|n| NonZeroU32::new(n).ok_or("at least 1"))
}

/// Parses `--bdpt-connection-roulette`: a share from 0 to 100.
pub fn connection_roulette() -> impl Fn(&str) -> Result<f32, String> + Clone + Send + Sync + 'static
{
    finite_f32(0.0, 100.0)
}

/// Parses `--exposure`: stops from -64 to 64.
pub fn exposure() -> impl Fn(&str) -> Result<f32, String> + Clone + Send + Sync + 'static {
    finite_f32(-64.0, 64.0)
}
