//! Measuring one configuration: frames from a fresh start, their GPU time, and the error of the
//! image against a many-sample reference at chosen frames.

use super::error::TradeoffError;
use crate::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_engine::capture::ImageData;
use lucid_engine::graph::{FrameOutputs, ReadbackId, RenderGraph};
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
    /// The time this measurement was taken for: a step of the [`Schedule`]'s targets, which
    /// `frame` is the first frame to reach (`gpu_ms - frame_ms < target_ms <= gpu_ms`, unless the
    /// frame before it reached the target unexpectedly: see [`Sampling`]). `None` for the last
    /// frame of a run that reached [`Limits::max_frames`] before its next target, and for another
    /// renderer's images.
    pub target_ms: Option<f64>,
    /// GPU milliseconds of all frames up to and including this one (wall milliseconds with
    /// [`Clock::Wall`]).
    pub gpu_ms: f64,
    /// GPU milliseconds of this frame alone (the last part of `gpu_ms`).
    pub frame_ms: f64,
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
    /// The measurements, by increasing time: one per target of the [`Schedule`] reached (a frame
    /// that reached several has a row for each), and one for the last frame if it reached none.
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

/// When the error is measured: at the first frame whose cumulative time reaches each of its
/// targets ([`Schedule::targets`]), and at the last frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Schedule {
    /// At the steps of [`time_ladder`] up to the budget: every configuration given the same
    /// budget is measured at the same times, whatever its time per frame (the error curves of
    /// `lucid converge`).
    TimeLadder,
    /// At the frame that spends the budget (or the last frame) only.
    Last,
}

impl Schedule {
    /// The cumulative times (ms) measured at, increasing; the last is `budget_ms`.
    pub fn targets(self, budget_ms: f64) -> Vec<f64> {
        match self {
            Schedule::TimeLadder => time_ladder(budget_ms),
            Schedule::Last => vec![budget_ms],
        }
    }
}

/// The steps of [`time_ladder`] in each decade: about 1.5 times apart (5/3 at most), as fine as
/// frames 1, 2, 3, 4, 6, 8, ... were before the schedule measured times, and round numbers for
/// tables.
pub const LADDER_STEPS: [f64; 6] = [1.0, 1.5, 2.0, 3.0, 5.0, 7.0];

/// How many decades below the budget [`time_ladder`] starts: a thousandth of the budget, the
/// time of one frame for a configuration that renders a thousand in the budget.
pub const LADDER_DECADES: i32 = 3;

/// The times (ms) `lucid converge` measures every configuration at: [`LADDER_STEPS`] times powers
/// of ten from a thousandth of `budget_ms` (inclusive) up to `budget_ms` (exclusive), then
/// `budget_ms` itself, increasing. A budget that is not a positive finite number is the only
/// step.
pub fn time_ladder(budget_ms: f64) -> Vec<f64> {
    if !(budget_ms.is_finite() && budget_ms > 0.0) {
        return vec![budget_ms];
    }
    let start = budget_ms / 10f64.powi(LADDER_DECADES);
    let first_decade = start.log10().floor() as i32;
    let last_decade = budget_ms.log10().floor() as i32;
    let mut ladder: Vec<f64> = (first_decade..=last_decade)
        .flat_map(|k| LADDER_STEPS.iter().map(move |&m| times_power_of_ten(m, k)))
        .filter(|&t| t >= start && t < budget_ms)
        .collect();
    ladder.push(budget_ms);
    ladder
}

/// `m * 10^k`, rounded once (a division for negative `k`, so `1.5e-1` is `0.15`).
fn times_power_of_ten(m: f64, k: i32) -> f64 {
    if k >= 0 {
        m * 10f64.powi(k)
    } else {
        m / 10f64.powi(-k)
    }
}

/// How far ahead a frame is read back: when the time reached before it plus `REACH` times the
/// frame before it reaches the next target. Frame times vary by up to about twice from one frame
/// to the next on lavapipe with other work on its CPU cores (`lucid bench`, 32x32), much less on a
/// GPU; a target costs up to `REACH` read-backs.
pub const REACH: f64 = 4.0;

/// Which frames of a run are read back and which targets each measures: plain data, told each
/// frame's time as it completes.
///
/// Whether a frame reaches a target is known only once it has run, but its HDR image must be read
/// back by the frame itself (the next frame overwrites it). So a frame is read back when it could
/// reach the next target: when no frame time is known yet (the first frame) or the time so far
/// plus [`REACH`] times the frame before it reaches it, and at [`Limits::max_frames`]. Frames
/// far from a target are not read back, so the frames still run back to back and the GPU does
/// not wait for copies to the host. A frame that reaches a target is measured for it (and for
/// every other target it reached); the frame that reaches the last target (the budget) is the
/// last. Only a frame taking more than [`REACH`] times the frame before it can reach a target
/// unread: the target is then measured at the next frame, which is read back since the time so
/// far has reached it, and its row shows it (`gpu_ms - frame_ms >= target_ms`).
#[derive(Clone, Debug, PartialEq)]
pub struct Sampling {
    targets: Vec<f64>,
    next: usize,
    max_frames: u32,
    frames: u32,
    elapsed_ms: f64,
    previous_ms: Option<f64>,
}

/// What one frame turned out to be, by [`Sampling::record`].
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// Whether the frame's image was read back ([`Sampling::reads_back_next`] before it).
    pub read_back: bool,
    /// The measurements the frame's image is for: the targets it is the first to reach, or one
    /// `None` for the last frame when it reached none. Empty for a frame not measured.
    pub targets: Vec<Option<f64>>,
    /// Whether the run ends with this frame.
    pub last: bool,
}

impl Sampling {
    /// A run measured at `schedule`'s targets for `limits.budget_ms`, ending at the frame that
    /// reaches the last of them or at `limits.max_frames` (at least 1).
    pub fn new(schedule: Schedule, limits: &Limits) -> Self {
        Self {
            targets: schedule.targets(limits.budget_ms),
            next: 0,
            max_frames: limits.max_frames.max(1),
            frames: 0,
            elapsed_ms: 0.0,
            previous_ms: None,
        }
    }

    /// Whether the next frame's HDR image is to be read back.
    pub fn reads_back_next(&self) -> bool {
        if self.frames + 1 >= self.max_frames {
            return true;
        }
        match (self.targets.get(self.next), self.previous_ms) {
            (None, _) => false,
            (Some(target), None) => target.is_finite(),
            (Some(&target), Some(previous)) => self.elapsed_ms + REACH * previous >= target,
        }
    }

    /// Records the next frame, which took `ms`: what it measures and whether it is the last.
    pub fn record(&mut self, ms: f64) -> Step {
        let read_back = self.reads_back_next();
        self.frames += 1;
        self.elapsed_ms += ms;
        self.previous_ms = Some(ms);
        let mut targets = Vec::new();
        if read_back {
            while let Some(&target) = self.targets.get(self.next) {
                if target > self.elapsed_ms {
                    break;
                }
                targets.push(Some(target));
                self.next += 1;
            }
        }
        let last = self.frames >= self.max_frames || self.next == self.targets.len();
        if last && read_back && targets.is_empty() {
            targets.push(None);
        }
        Step {
            read_back,
            targets,
            last,
        }
    }

    /// Frames recorded.
    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// Milliseconds of the frames recorded.
    pub fn elapsed_ms(&self) -> f64 {
        self.elapsed_ms
    }
}

/// How long a configuration renders.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Frames rendered first and not measured (pipeline creation, caches), before the
    /// configuration starts afresh (accumulation and histories reset).
    pub warmup: u32,
    /// Most frames, whatever the budget (at least 1).
    pub max_frames: u32,
    /// GPU milliseconds after which no further frame starts (once the frame that spent them was
    /// measured: see [`Sampling`]).
    pub budget_ms: f64,
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
    })?;
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

/// Renders `limits.warmup` frames of `settings`, then frames from a fresh start until the frame
/// that spends `limits.budget_ms` or `limits.max_frames`, measuring the error of the frame's HDR
/// image (accumulated and denoised as `settings` say) against `reference` (prepared with the
/// display mapping of `settings`) at the first frame to reach each of `schedule`'s target times
/// and at the last (see [`Sampling`]). `on_frame` is called after each measured-time frame.
///
/// The frames run back to back as in `lucid bench`: the HDR image is read back only from the
/// frames that may reach a target ([`Sampling::reads_back_next`]) and kept only from those that
/// did, and the errors are computed after the last frame, so the GPU does not idle between
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
    renderer.set_settings(settings)?;
    for _ in 0..limits.warmup {
        renderer.render()?;
    }
    renderer.finish()?;
    renderer.cut();
    let mut sampling = Sampling::new(schedule, &limits);
    let mut kept = Vec::new();
    loop {
        let frame = render_timed(renderer, sampling.reads_back_next(), clock)?;
        let step = sampling.record(frame.ms);
        if let (Some(hdr), false) = (frame.hdr, step.targets.is_empty()) {
            kept.push(Kept {
                frame: sampling.frames(),
                gpu_ms: sampling.elapsed_ms(),
                frame_ms: frame.ms,
                targets: step.targets,
                image: frame.outputs.image(hdr)?,
            });
        }
        on_frame();
        if step.last {
            break;
        }
    }
    renderer.finish()?;
    let mut rows = Vec::new();
    for k in &kept {
        rows.extend(k.evaluate(reference, &config)?);
    }
    Ok(ConfigResult {
        config,
        rows,
        frames: sampling.frames(),
        gpu_ms: sampling.elapsed_ms(),
    })
}

/// A measured frame's image, kept until the run ends.
struct Kept {
    frame: u32,
    gpu_ms: f64,
    frame_ms: f64,
    targets: Vec<Option<f64>>,
    image: ImageData,
}

impl Kept {
    /// The frame's errors against `reference`, one row per target it was measured for.
    fn evaluate(
        &self,
        reference: &PreparedReference,
        config: &Config,
    ) -> Result<Vec<Measurement>, TradeoffError> {
        let m = reference
            .evaluate(&self.image)
            .map_err(|source| TradeoffError::Metrics {
                config: config.name(),
                source,
            })?;
        Ok(self
            .targets
            .iter()
            .map(|&target_ms| Measurement {
                frame: self.frame,
                target_ms,
                gpu_ms: self.gpu_ms,
                frame_ms: self.frame_ms,
                dssim: m.dssim,
                flip: m.flip,
                rel_mse: m.rel_mse,
            })
            .collect())
    }
}

/// A frame rendered by [`render_timed`].
struct TimedFrame {
    /// Its time by the run's clock.
    ms: f64,
    /// What it returned.
    outputs: FrameOutputs,
    /// Its HDR image in `outputs`, where read back.
    hdr: Option<ReadbackId>,
}

/// Renders one frame and waits for it: its time by `clock` and, when `read_back`, its HDR image
/// (converted only where it is kept).
fn render_timed(
    renderer: &mut Renderer,
    read_back: bool,
    clock: Clock,
) -> Result<TimedFrame, TradeoffError> {
    let mut g = RenderGraph::new();
    let (frame_images, stats) = renderer.add_frame(&mut g);
    // The displayed image leaves the graph as in `lucid bench` (its passes are part of a
    // frame); the HDR image is what is measured.
    g.readback(frame_images.ldr);
    let hdr = read_back.then(|| g.readback(frame_images.hdr));
    let started = Instant::now();
    let submitted = renderer
        .executor_mut()
        .execute(g.compile().map_err(EngineError::from)?)?;
    let outputs = renderer.executor_mut().wait(submitted)?;
    let wall_ms = started.elapsed().as_secs_f64() * 1e3;
    renderer.collect_stats(&outputs, stats)?;
    let ms = match clock {
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
    Ok(TimedFrame { ms, outputs, hdr })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ladder_steps_one_to_seven_per_decade_from_a_thousandth_of_the_budget() {
        assert_eq!(
            time_ladder(1300.0),
            [
                1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 15.0, 20.0, 30.0, 50.0, 70.0, 100.0, 150.0, 200.0,
                300.0, 500.0, 700.0, 1000.0, 1300.0
            ]
        );
        // A budget on the ladder is its last step once; the start is included.
        let ladder = time_ladder(30.0);
        assert_eq!(ladder.first(), Some(&0.03));
        assert_eq!(ladder.last(), Some(&30.0));
        assert_eq!(ladder.len(), 3 * LADDER_STEPS.len() + 1);
        assert!(ladder
            .windows(2)
            .all(|w| w[1] > w[0] && w[1] / w[0] <= 5.0 / 3.0));
        assert_eq!(time_ladder(f64::INFINITY), [f64::INFINITY]);
        assert_eq!(Schedule::Last.targets(30.0), [30.0]);
        assert_eq!(Schedule::TimeLadder.targets(30.0), ladder);
    }

    /// Records frames of `times` (ms) until the last: what each turned out to be.
    fn run(schedule: Schedule, budget_ms: f64, max_frames: u32, times: &[f64]) -> Vec<Step> {
        let limits = Limits {
            warmup: 0,
            max_frames,
            budget_ms,
        };
        let mut sampling = Sampling::new(schedule, &limits);
        let mut steps = Vec::new();
        for &ms in times {
            let step = sampling.record(ms);
            let last = step.last;
            steps.push(step);
            if last {
                break;
            }
        }
        steps
    }

    fn step(read_back: bool, targets: &[f64], last: bool) -> Step {
        Step {
            read_back,
            targets: targets.iter().map(|&t| Some(t)).collect(),
            last,
        }
    }

    #[test]
    fn each_target_is_measured_at_the_first_frame_to_reach_it() {
        // Budget 10 ms: targets 0.01 .. 7 and 10. Frames of 2 ms: the first reaches every target
        // up to 2 ms, each later one the one it passes (all within four frame times of the next,
        // so all read back).
        let steps = run(Schedule::TimeLadder, 10.0, 100, &[2.0; 10]);
        let below_two: Vec<f64> = time_ladder(10.0)
            .into_iter()
            .filter(|&t| t <= 2.0)
            .collect();
        assert_eq!(
            steps,
            [
                step(true, &below_two, false),
                step(true, &[3.0], false),
                step(true, &[5.0], false),
                step(true, &[7.0], false),
                step(true, &[10.0], true),
            ]
        );
    }

    #[test]
    fn frames_far_from_the_next_target_are_not_read_back() {
        // Budget 100 ms, 1 ms frames: after 20 ms the next target is 30 ms, so frames 21 to 26
        // (ending at 21 to 26 ms) are not read back; frames 27 to 29 could reach it within four
        // frame times and are read back but reach nothing; frame 30 reaches it.
        let steps = run(Schedule::TimeLadder, 100.0, 1000, &[1.0; 100]);
        let read: Vec<bool> = steps[20..30].iter().map(|s| s.read_back).collect();
        assert_eq!(
            read,
            [false, false, false, false, false, false, true, true, true, true]
        );
        assert!(steps[26..29].iter().all(|s| s.targets.is_empty()));
        assert_eq!(steps[29].targets, [Some(30.0)]);
        assert_eq!(steps.len(), 100);
        assert_eq!(steps[99].targets, [Some(100.0)]);
        assert!(steps[99].last);
    }

    #[test]
    fn a_frame_that_reaches_a_target_unexpectedly_leaves_it_to_the_next() {
        // 1 ms frames, then one of 10 ms from 10 ms that passes the 15 and 20 ms targets unread:
        // the next frame is read back and measured for both.
        let mut times = vec![1.0; 10];
        times.extend([10.0, 1.0]);
        let steps = run(Schedule::TimeLadder, 100.0, 1000, &times);
        assert_eq!(steps[10], step(false, &[], false));
        assert_eq!(steps[11], step(true, &[15.0, 20.0], false));
    }

    #[test]
    fn the_run_ends_at_the_frame_limit_with_its_last_frame_measured() {
        let steps = run(Schedule::TimeLadder, 100.0, 10, &[1.0; 20]);
        assert_eq!(steps.len(), 10);
        assert_eq!(steps[9], step(true, &[10.0], true));
        // A last frame that reaches no target (the next is 15 ms) is measured without one.
        let steps = run(Schedule::TimeLadder, 100.0, 12, &[1.0; 20]);
        assert_eq!(steps.len(), 12);
        assert!(!steps[10].read_back);
        assert_eq!(
            steps[11],
            Step {
                read_back: true,
                targets: vec![None],
                last: true
            }
        );
    }

    #[test]
    fn the_last_schedule_measures_only_the_frame_that_spends_the_budget() {
        let steps = run(Schedule::Last, 10.0, 100, &[1.0; 20]);
        let read: Vec<bool> = steps.iter().map(|s| s.read_back).collect();
        assert_eq!(
            read,
            [true, false, false, false, false, false, true, true, true, true]
        );
        let measured: Vec<usize> = (0..steps.len())
            .filter(|&i| !steps[i].targets.is_empty())
            .collect();
        assert_eq!(measured, [9]);
        assert_eq!(steps[9], step(true, &[10.0], true));
        // Without a budget, only the last frame of the limit is read back.
        let steps = run(Schedule::Last, f64::INFINITY, 4, &[1.0; 10]);
        let read: Vec<bool> = steps.iter().map(|s| s.read_back).collect();
        assert_eq!(read, [false, false, false, true]);
        assert_eq!(steps[3].targets, [None]);
    }

    #[test]
    fn configurations_list_every_combination_in_order() {
        let spp = [SamplesPerPixel::ONE, SamplesPerPixel::new(4).unwrap()];
        let algorithms = [Algorithm::PathTracing, Algorithm::Bidirectional];
        let all = Config::all(&algorithms, &[Denoiser::Svgf], &spp);
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
