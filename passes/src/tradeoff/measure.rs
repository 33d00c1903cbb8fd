//! Measuring one configuration: frames from a fresh start, their GPU time, and the error of the
//! image against a many-sample reference at chosen frames.

use super::error::TradeoffError;
use crate::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_engine::graph::RenderGraph;
use lucid_engine::metrics::PreparedReference;
use lucid_engine::{Context, EngineError};
use std::time::Instant;

/// Samples per pixel per frame of reference renders (more are accumulated over frames).
pub const REFERENCE_SPP_PER_FRAME: SamplesPerPixel = SamplesPerPixel::new(16).unwrap();

/// What the reference's seed is xor-ed with, so its noise is independent of the configurations'.
pub const REFERENCE_SEED_XOR: u32 = 0x9e37_79b9;

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

    /// `base` with this configuration's algorithm, denoiser and samples per pixel.
    pub fn apply(&self, base: Settings) -> Settings {
        Settings {
            algorithm: self.algorithm,
            denoiser: self.denoiser,
            samples_per_pixel: self.spp,
            ..base
        }
    }

    /// Every configuration of the lists, algorithm first, then denoiser, then samples per pixel.
    pub fn all(
        algorithms: &[Algorithm],
        denoisers: &[Denoiser],
        spp: &[SamplesPerPixel],
    ) -> Vec<Config> {
        algorithms
            .iter()
            .flat_map(|&algorithm| {
                denoisers.iter().flat_map(move |&denoiser| {
                    spp.iter().map(move |&spp| Config {
                        algorithm,
                        denoiser,
                        spp,
                    })
                })
            })
            .collect()
    }
}

/// The error of a configuration's image after `frame` frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measurement {
    /// Frames rendered (1 for the first).
    pub frame: u32,
    /// GPU milliseconds of all frames up to and including this one (wall milliseconds with
    /// [`Clock::Wall`]).
    pub gpu_ms: f64,
    /// `1 / SSIM - 1`.
    pub dssim: f64,
    /// Mean FLIP.
    pub flip: f64,
    /// Relative MSE.
    pub rel_mse: f64,
}

/// What one configuration did.
#[derive(Clone, Debug, PartialEq)]
pub struct ConfigResult {
    /// The configuration.
    pub config: Config,
    /// The measurements, at the frames the [`Schedule`] picks.
    pub rows: Vec<Measurement>,
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
    pub fn last(&self) -> Option<&Measurement> {
        self.rows.last()
    }
}

/// How frame times are measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// GPU timestamps around each pass, summed.
    Gpu,
    /// Wall time from submission to completion (devices without timestamp queries).
    Wall,
}

impl Clock {
    /// GPU timestamps where the device has them, else wall time.
    pub fn of(ctx: &Context) -> Self {
        if ctx.info().timestamps {
            Clock::Gpu
        } else {
            Clock::Wall
        }
    }

    /// `gpu` or `wall` (the JSON's `time`).
    pub fn name(self) -> &'static str {
        match self {
            Clock::Gpu => "gpu",
            Clock::Wall => "wall",
        }
    }

    /// `GPU time` or `wall time`.
    pub fn label(self) -> &'static str {
        match self {
            Clock::Gpu => "GPU time",
            Clock::Wall => "wall time",
        }
    }
}

/// When the error is measured, besides the last frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Schedule {
    /// At the frames [`measured`] picks (the error curve of `lucid converge`).
    Geometric,
    /// At the last frame only.
    Last,
}

/// How long a configuration renders.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Frames rendered first and not measured (pipeline creation, caches), before the
    /// configuration starts afresh (accumulation and histories reset).
    pub warmup: u32,
    /// Most frames, whatever the budget (at least 1).
    pub max_frames: u32,
    /// GPU milliseconds after which no further frame starts.
    pub budget_ms: f64,
}

/// Whether the error is measured after `frame` frames with [`Schedule::Geometric`] (besides the
/// last frame): frames 1, 2, 3, 4, 6, 8, 12, 16, 24, ... (powers of two and three times them), so a
/// long run costs few measurements.
pub fn measured(frame: u32) -> bool {
    frame.is_power_of_two() || (frame % 3 == 0 && (frame / 3).is_power_of_two())
}

/// Renders the reference: `algorithm` without a denoiser, `spp` samples per pixel accumulated
/// over frames of [`REFERENCE_SPP_PER_FRAME`], with the seed of `base` xor [`REFERENCE_SEED_XOR`]
/// so its noise is independent of the configurations'; prepared for [`measure`] with the display
/// mapping of `base`. `on_frame` is called after each frame.
pub fn render_reference(
    renderer: &mut Renderer,
    base: Settings,
    algorithm: Algorithm,
    spp: SamplesPerPixel,
    on_frame: &mut dyn FnMut(),
) -> Result<PreparedReference, TradeoffError> {
    renderer.set_settings(Settings {
        algorithm,
        denoiser: Denoiser::None,
        samples_per_pixel: spp.min(REFERENCE_SPP_PER_FRAME),
        seed: base.seed ^ REFERENCE_SEED_XOR,
        accumulate: true,
        ..base
    });
    renderer.cut();
    let frames = spp.get().div_ceil(REFERENCE_SPP_PER_FRAME.get());
    for _ in 1..frames {
        renderer.render()?;
        on_frame();
    }
    let image = renderer.render_and_read()?;
    on_frame();
    if image.has_non_finite() {
        return Err(TradeoffError::NonFiniteReference);
    }
    PreparedReference::new(&image, &base.display).map_err(|source| TradeoffError::Metrics {
        config: "reference".into(),
        source,
    })
}

/// Renders `limits.warmup` frames of `settings`, then frames from a fresh start until
/// `limits.budget_ms` is spent or `limits.max_frames` reached, measuring the error of the frame's
/// HDR image (accumulated and denoised as `settings` say) against `reference` (prepared with the
/// display mapping of `settings`) at the frames `schedule` picks and at the last. `on_frame` is
/// called after each measured-time frame.
///
/// The frames run back to back as in `lucid bench`: the HDR image is read back only from the
/// frames measured (and from those that may be the last, when the next frame could spend the
/// budget), and the errors are computed after the last frame, so the GPU does not idle between
/// frames while the host computes metrics (an idle GPU lowers its clocks, and the frames after
/// it would take longer than they do in a running application).
pub fn measure(
    renderer: &mut Renderer,
    settings: Settings,
    reference: &PreparedReference,
    limits: Limits,
    schedule: Schedule,
    clock: Clock,
    on_frame: &mut dyn FnMut(),
) -> Result<ConfigResult, TradeoffError> {
    let config = Config {
        algorithm: settings.algorithm,
        denoiser: settings.denoiser,
        spp: settings.samples_per_pixel,
    };
    renderer.set_settings(settings);
    for _ in 0..limits.warmup {
        renderer.render()?;
    }
    renderer.finish()?;
    renderer.cut();
    let max_frames = limits.max_frames.max(1);
    let mut images = Vec::new();
    let mut gpu_ms = 0.0;
    let mut frames = 0;
    loop {
        let frame = frames + 1;
        let mean_ms = if frames > 0 {
            gpu_ms / f64::from(frames)
        } else {
            0.0
        };
        let may_be_last = frame == max_frames || gpu_ms + 1.5 * mean_ms >= limits.budget_ms;
        let wanted = may_be_last || (schedule == Schedule::Geometric && measured(frame));
        let mut g = RenderGraph::new();
        let (frame_images, stats) = renderer.add_frame(&mut g);
        // The displayed image leaves the graph as in `lucid bench` (its passes are part of a
        // frame); the HDR image is what is measured.
        g.readback(frame_images.ldr);
        let hdr = wanted.then(|| g.readback(frame_images.hdr));
        let started = Instant::now();
        let submitted = renderer
            .executor_mut()
            .execute(g.compile().map_err(EngineError::from)?)?;
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
        // A frame that spent the budget without its image read back is followed by one more.
        let last = frame == max_frames || (gpu_ms >= limits.budget_ms && hdr.is_some());
        if let Some(hdr) = hdr {
            if last || (schedule == Schedule::Geometric && measured(frame)) {
                images.push((frame, gpu_ms, outputs.image(hdr)?));
            }
        }
        on_frame();
        if last {
            break;
        }
    }
    renderer.finish()?;
    let rows = images
        .iter()
        .map(|(frame, gpu_ms, image)| {
            let m = reference
                .evaluate(image)
                .map_err(|source| TradeoffError::Metrics {
                    config: config.name(),
                    source,
                })?;
            Ok(Measurement {
                frame: *frame,
                gpu_ms: *gpu_ms,
                dssim: m.dssim,
                flip: m.flip,
                rel_mse: m.rel_mse,
            })
        })
        .collect::<Result<Vec<_>, TradeoffError>>()?;
    Ok(ConfigResult {
        config,
        rows,
        frames,
        gpu_ms,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_are_measured_at_geometrically_spaced_frames() {
        let frames: Vec<u32> = (1..=50).filter(|&f| measured(f)).collect();
        assert_eq!(frames, [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48]);
    }

    #[test]
    fn configurations_list_every_combination_in_order() {
        let spp = [SamplesPerPixel::ONE, SamplesPerPixel::new(4).unwrap()];
        let all = Config::all(&Algorithm::ALL, &[Denoiser::Svgf], &spp);
        let names: Vec<String> = all.iter().map(Config::name).collect();
        assert_eq!(
            names,
            ["pt/svgf/1", "pt/svgf/4", "bdpt/svgf/1", "bdpt/svgf/4"]
        );
        let settings = all[3].apply(Settings::default());
        assert_eq!(settings.algorithm, Algorithm::Bidirectional);
        assert_eq!(settings.samples_per_pixel.get(), 4);
    }
}
