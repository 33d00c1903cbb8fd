//! `--algo auto`: a short calibration on the scene measures every candidate configuration for time
//! per frame and error against a many-sample reference, then [`Calibration::choose`] picks the
//! cheapest configuration on the Pareto front that meets a quality target, or the most accurate
//! within a frame budget.
//!
//! What is measured is the image a real-time frame shows: accumulation off (as while the camera
//! moves), the still camera letting the denoisers' histories build up over
//! [`CalibrationOptions::frames`] frames, the error taken at the last of them and the time averaged
//! over all of them (after a warm-up frame that is not measured).

use super::error::TradeoffError;
use super::measure::{self, Clock, Config, ConfigResult, Limits, Schedule};
use super::metric::Metric;
use super::pareto::pareto_front;
use crate::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel};
use lucid_engine::context::DeviceKind;
use lucid_engine::Context;
use std::time::Instant;

/// What the choice must achieve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Goal {
    /// The cheapest configuration whose `metric` is at most `target`.
    Quality {
        /// The error the target is in.
        metric: Metric,
        /// The largest acceptable error.
        target: f64,
    },
    /// The configuration with the smallest `metric` taking at most `ms` per frame.
    Budget {
        /// The error to minimise.
        metric: Metric,
        /// Milliseconds per frame (GPU time, or wall time where the device has no timestamps).
        ms: f64,
    },
}

impl Goal {
    /// The metric the goal is stated in.
    pub fn metric(&self) -> Metric {
        match *self {
            Goal::Quality { metric, .. } | Goal::Budget { metric, .. } => metric,
        }
    }

    /// `FLIP <= 0.1` or `at most 8 ms per frame, least FLIP`.
    pub fn describe(&self) -> String {
        match *self {
            Goal::Quality { metric, target } => format!("{} <= {target}", metric.label()),
            Goal::Budget { metric, ms } => {
                format!(
                    "at most {} ms per frame, least {}",
                    short(ms),
                    metric.label()
                )
            }
        }
    }
}

/// The candidates and how long each is measured.
#[derive(Clone, Debug, PartialEq)]
pub struct CalibrationOptions {
    /// Light-transport algorithms (bidirectional path tracing is left out, with a note, on a device
    /// without 64-bit integer atomics).
    pub algorithms: Vec<Algorithm>,
    /// Denoisers.
    pub denoisers: Vec<Denoiser>,
    /// Samples per pixel per frame.
    pub spp: Vec<SamplesPerPixel>,
    /// Frames each candidate renders from a fresh start; the error is that of the last.
    pub frames: u32,
    /// Frames each candidate renders first, not measured.
    pub warmup: u32,
    /// Samples per pixel of the path-traced reference.
    pub reference_spp: SamplesPerPixel,
}

impl Default for CalibrationOptions {
    /// Path tracing and BDPT, every denoiser, 1, 2 and 4 samples per pixel, 8 frames each after one
    /// warm-up frame, a 256-sample reference.
    fn default() -> Self {
        let spp = |n| SamplesPerPixel::new(n).expect("not zero");
        Self {
            // The wavefront path tracer computes path tracing's estimator: measuring it too
            // would double the calibration for the same errors.
            algorithms: vec![Algorithm::PathTracing, Algorithm::Bidirectional],
            denoisers: Denoiser::ALL.to_vec(),
            spp: vec![spp(1), spp(2), spp(4)],
            frames: 8,
            warmup: 1,
            reference_spp: spp(256),
        }
    }
}

impl CalibrationOptions {
    /// The default options on a GPU; on a software device (lavapipe), where each candidate frame
    /// takes CPU time, a shorter calibration: no learned denoiser (the slowest there), 1 and 2
    /// samples per pixel, 4 frames each and a 64-sample reference.
    pub fn for_device(ctx: &Context) -> Self {
        let defaults = Self::default();
        if ctx.info().kind != DeviceKind::Cpu {
            return defaults;
        }
        let spp = |n| SamplesPerPixel::new(n).expect("not zero");
        Self {
            denoisers: vec![Denoiser::None, Denoiser::Svgf],
            spp: vec![spp(1), spp(2)],
            frames: 4,
            reference_spp: spp(64),
            ..defaults
        }
    }

    /// Frames [`calibrate`] renders in all for `candidates` configurations (for progress bars).
    pub fn total_frames(&self, candidates: usize) -> u64 {
        let reference = self
            .reference_spp
            .get()
            .div_ceil(measure::REFERENCE_SPP_PER_FRAME.get());
        u64::from(reference) + candidates as u64 * u64::from(self.frames.max(1))
    }
}

/// What a calibration measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Calibration {
    /// One result per candidate, in [`Config::all`]'s order; each with one measurement, at its
    /// last frame.
    pub results: Vec<ConfigResult>,
    /// How times were measured.
    pub clock: Clock,
    /// What was left out and why.
    pub notes: Vec<String>,
    /// The image size measured at.
    pub size: (u32, u32),
    /// Wall-clock seconds the calibration took.
    pub seconds: f64,
}

/// The configuration a goal picks, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    /// The configuration.
    pub config: Config,
    /// Its time per frame, in the calibration's clock.
    pub ms_per_frame: f64,
    /// Its error in the goal's metric.
    pub error: f64,
    /// Whether it meets the goal (when none does, the choice is the closest: the most accurate
    /// for a quality target, the fastest for a budget).
    pub met: bool,
    /// One sentence for people: what was chosen, against what, and what the runner-up of the
    /// other algorithm would have given.
    pub reason: String,
}

/// Measures every candidate of `options` on `renderer` (its scene, camera and size; its other
/// settings, such as the path length and the display, as they are) and returns what was measured.
/// The renderer's settings are restored afterwards and its accumulation restarts. `on_frame` is
/// called after each frame (for progress bars: [`CalibrationOptions::total_frames`] in all).
pub fn calibrate(
    renderer: &mut Renderer,
    options: &CalibrationOptions,
    on_frame: &mut dyn FnMut(),
) -> Result<Calibration, TradeoffError> {
    let started = Instant::now();
    let saved = *renderer.settings();
    let ctx = renderer.executor().context().clone();
    let info = ctx.info();
    let mut notes = Vec::new();
    let mut algorithms = options.algorithms.clone();
    if !info.int64_atomics && algorithms.contains(&Algorithm::Bidirectional) {
        algorithms.retain(|a| *a != Algorithm::Bidirectional);
        notes.push(format!(
            "bdpt left out: {} has no 64-bit integer atomics (its light tracing splats need them)",
            info.name
        ));
    }
    let candidates = Config::all(&algorithms, &options.denoisers, &options.spp);
    if candidates.is_empty() {
        return Err(TradeoffError::NoCandidates(if notes.is_empty() {
            "the lists of algorithms, denoisers and samples per pixel must not be empty".into()
        } else {
            notes.join("; ")
        }));
    }
    // Bidirectional path tracing converges where path tracing's reference would still be noisy
    // (caustics, lights seen through a gap) and to the same image elsewhere.
    let reference_algorithm = if info.int64_atomics {
        Algorithm::Bidirectional
    } else {
        Algorithm::PathTracing
    };
    let clock = Clock::of(&ctx);
    if clock == Clock::Wall {
        notes.push(format!(
            "{} has no timestamp queries: times are wall times",
            info.name
        ));
    }
    let measured = (|| {
        let reference = measure::render_reference(
            renderer,
            saved,
            reference_algorithm,
            options.reference_spp,
            on_frame,
        )?;
        let limits = Limits {
            warmup: options.warmup,
            max_frames: options.frames.max(1),
            budget_ms: f64::INFINITY,
        };
        candidates
            .iter()
            .map(|config| {
                let settings = config.apply(saved);
                let realtime = crate::renderer::Settings {
                    accumulate: false,
                    ..settings
                };
                measure::measure(
                    renderer,
                    realtime,
                    &reference,
                    limits,
                    Schedule::Last,
                    clock,
                    on_frame,
                )
            })
            .collect::<Result<Vec<_>, _>>()
    })();
    renderer.set_settings(saved)?;
    renderer.cut();
    Ok(Calibration {
        results: measured?,
        clock,
        notes,
        size: renderer.size(),
        seconds: started.elapsed().as_secs_f64(),
    })
}

impl Calibration {
    /// Per result, (ms per frame, final `metric`).
    pub fn points(&self, metric: Metric) -> Vec<(f64, f64)> {
        self.results
            .iter()
            .map(|r| {
                let error = r.last().map_or(f64::NAN, |row| metric.of(row));
                (r.ms_per_frame(), error)
            })
            .collect()
    }

    /// The indices of the results on the Pareto front of time per frame and `metric`, fastest
    /// first.
    pub fn front(&self, metric: Metric) -> Vec<usize> {
        pareto_front(&self.points(metric))
    }

    /// The configuration on the Pareto front that `goal` picks: for a quality target, the
    /// cheapest whose error is at most the target (else the most accurate); for a budget, the
    /// most accurate within it (else the fastest). An error only when no result has a finite
    /// time and error.
    pub fn choose(&self, goal: Goal) -> Result<Choice, TradeoffError> {
        let metric = goal.metric();
        let points = self.points(metric);
        let front = pareto_front(&points);
        let (index, met) = match goal {
            // The front runs from fastest (least accurate) to slowest (most accurate).
            Goal::Quality { target, .. } => match front.iter().find(|&&i| points[i].1 <= target) {
                Some(&i) => (Some(i), true),
                None => (front.last().copied(), false),
            },
            Goal::Budget { ms, .. } => match front.iter().rev().find(|&&i| points[i].0 <= ms) {
                Some(&i) => (Some(i), true),
                None => (front.first().copied(), false),
            },
        };
        let index = index.ok_or_else(|| {
            TradeoffError::NoCandidates(format!(
                "no configuration has a finite time and {}",
                metric.label()
            ))
        })?;
        let config = self.results[index].config;
        let (ms_per_frame, error) = points[index];
        Ok(Choice {
            config,
            ms_per_frame,
            error,
            met,
            reason: self.reason(goal, index, met),
        })
    }

    /// Why `goal` picked result `index`.
    fn reason(&self, goal: Goal, index: usize, met: bool) -> String {
        let metric = goal.metric();
        let points = self.points(metric);
        let unit = match self.clock {
            Clock::Gpu => "ms per frame",
            Clock::Wall => "ms per frame (wall time)",
        };
        let describe = |i: usize| {
            format!(
                "{} ({} {:.4} at {:.3} {unit})",
                self.results[i].config.name(),
                metric.label(),
                points[i].1,
                points[i].0
            )
        };
        let chosen = describe(index);
        let n = self.results.len();
        let (w, h) = self.size;
        let lead = match (goal, met) {
            (Goal::Quality { target, .. }, true) => format!(
                "{chosen}: the cheapest of {n} configurations measured at {w}x{h} with {} <= {target}",
                metric.label()
            ),
            (Goal::Quality { target, .. }, false) => format!(
                "{chosen}: no configuration of {n} measured at {w}x{h} reaches {} <= {target}; this is the most accurate",
                metric.label()
            ),
            (Goal::Budget { ms, .. }, true) => format!(
                "{chosen}: the least {} of {n} configurations measured at {w}x{h} within {} {unit}",
                metric.label(),
                short(ms)
            ),
            (Goal::Budget { ms, .. }, false) => format!(
                "{chosen}: no configuration of {n} measured at {w}x{h} fits in {} {unit}; this is the fastest",
                short(ms)
            ),
        };
        let algorithm = self.results[index].config.algorithm;
        let others: Vec<usize> = (0..n)
            .filter(|&i| self.results[i].config.algorithm != algorithm)
            .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
            .collect();
        // The other algorithm's best answer to the same goal: its configuration that `keep`s with
        // the least error (`by_error`) or time.
        let other = algorithm.other().label();
        let best = |keep: &dyn Fn(usize) -> bool, by_error: bool| {
            let key = |i: usize| if by_error { points[i].1 } else { points[i].0 };
            others
                .iter()
                .copied()
                .filter(|&i| keep(i))
                .min_by(|&a, &b| key(a).total_cmp(&key(b)))
        };
        let (time, error) = (false, true);
        let runner_up = match goal {
            Goal::Quality { target, .. } => best(&|i| points[i].1 <= target, time)
                .map(|i| format!("the cheapest {other} that does is {}", describe(i)))
                .or_else(|| {
                    best(&|_| true, error)
                        .map(|i| format!("no {other} does: its most accurate is {}", describe(i)))
                }),
            Goal::Budget { ms, .. } => best(&|i| points[i].0 <= ms, error)
                .map(|i| format!("the most accurate {other} within it is {}", describe(i)))
                .or_else(|| {
                    best(&|_| true, time)
                        .map(|i| format!("no {other} fits: its fastest is {}", describe(i)))
                }),
        };
        match runner_up {
            Some(runner_up) => format!("{lead}; {runner_up}"),
            None => lead,
        }
    }
}

/// `ms` with at most three decimals (`16.667`, `8`).
fn short(ms: f64) -> f64 {
    (ms * 1e3).round() / 1e3
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tradeoff::Measurement;

    /// A calibration of made-up results: (algorithm, denoiser, spp, ms per frame, FLIP).
    fn calibration(points: &[(Algorithm, Denoiser, u32, f64, f64)]) -> Calibration {
        Calibration {
            results: points
                .iter()
                .map(|&(algorithm, denoiser, spp, ms, flip)| ConfigResult {
                    config: Config {
                        algorithm,
                        denoiser,
                        spp: SamplesPerPixel::new(spp).unwrap(),
                    },
                    rows: vec![Measurement {
                        frame: 4,
                        target_ms: None,
                        gpu_ms: 4.0 * ms,
                        frame_ms: ms,
                        dssim: 2.0 * flip,
                        flip,
                        rel_mse: flip * flip,
                    }],
                    frames: 4,
                    gpu_ms: 4.0 * ms,
                })
                .collect(),
            clock: Clock::Gpu,
            notes: Vec::new(),
            size: (64, 64),
            seconds: 1.0,
        }
    }

    use Algorithm::{Bidirectional as Bdpt, PathTracing as Pt};
    use Denoiser::{None as Raw, Svgf};

    fn sample() -> Calibration {
        calibration(&[
            (Pt, Raw, 1, 1.0, 0.30),
            (Pt, Svgf, 1, 2.0, 0.12),
            (Pt, Svgf, 4, 6.0, 0.08),
            (Bdpt, Raw, 1, 3.0, 0.20),
            (Bdpt, Svgf, 1, 4.0, 0.06),
            (Bdpt, Svgf, 4, 12.0, 0.07), // dominated by bdpt/svgf/1
        ])
    }

    fn quality(target: f64) -> Goal {
        Goal::Quality {
            metric: Metric::Flip,
            target,
        }
    }

    fn budget(ms: f64) -> Goal {
        Goal::Budget {
            metric: Metric::Flip,
            ms,
        }
    }

    #[test]
    fn a_quality_target_picks_the_cheapest_configuration_meeting_it() {
        let c = sample();
        let pick = c.choose(quality(0.15)).unwrap();
        assert_eq!(pick.config.name(), "pt/svgf/1");
        assert!(pick.met);
        assert_eq!((pick.ms_per_frame, pick.error), (2.0, 0.12));
        let pick = c.choose(quality(0.07)).unwrap();
        assert_eq!(pick.config.name(), "bdpt/svgf/1");
        assert!(
            pick.reason
                .contains("no path tracing does: its most accurate is pt/svgf/4"),
            "{}",
            pick.reason
        );
        let pick = c.choose(quality(0.01)).unwrap();
        assert_eq!(pick.config.name(), "bdpt/svgf/1", "the most accurate");
        assert!(!pick.met);
        assert!(pick.reason.contains("no configuration"), "{}", pick.reason);
    }

    #[test]
    fn a_budget_picks_the_most_accurate_configuration_within_it() {
        let c = sample();
        let pick = c.choose(budget(3.5)).unwrap();
        assert_eq!(pick.config.name(), "pt/svgf/1");
        assert!(pick.met);
        assert!(
            pick.reason
                .contains("the most accurate bidirectional within it is bdpt/none/1"),
            "{}",
            pick.reason
        );
        assert_eq!(
            c.choose(budget(100.0)).unwrap().config.name(),
            "bdpt/svgf/1"
        );
        let pick = c.choose(budget(0.5)).unwrap();
        assert_eq!(pick.config.name(), "pt/none/1", "the fastest");
        assert!(!pick.met);
    }

    #[test]
    fn every_choice_is_on_the_pareto_front() {
        let c = sample();
        let front = c.front(Metric::Flip);
        for goal in [0.5, 0.2, 0.1, 0.07, 0.0]
            .map(quality)
            .into_iter()
            .chain([0.0, 1.5, 3.0, 5.0, 50.0].map(budget))
        {
            let pick = c.choose(goal).unwrap();
            let index = c.results.iter().position(|r| r.config == pick.config);
            assert!(front.contains(&index.unwrap()), "{goal:?}: {}", pick.reason);
        }
    }

    #[test]
    fn no_finite_result_is_an_error() {
        let c = calibration(&[(Pt, Raw, 1, 1.0, f64::NAN)]);
        assert!(c.choose(quality(0.1)).is_err());
    }
}
