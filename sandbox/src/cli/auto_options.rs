//! `--algo auto` on the command line (`render`, `bench`, `sequence`): the goal (`--quality` or
//! `--budget-ms`, in `--quality-metric`), the calibration's length, and the table and choice it
//! prints.

use super::float_range::finite_f64;
use super::progress::Progress;
use super::render_options::samples_per_pixel;
use clap::builder::PossibleValue;
use clap::{Args, ValueEnum};
use lucid_passes::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel};
use lucid_passes::tradeoff::{calibrate, Calibration, CalibrationOptions, Choice, Goal, Metric};
use std::fmt::Write as _;

/// The frame budget without `--quality` or `--budget-ms`: 60 frames per second.
pub const DEFAULT_BUDGET_MS: f64 = 1000.0 / 60.0;

/// `--algo`: an algorithm, or `auto` for a calibration that picks the configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlgoArg {
    /// This algorithm.
    Fixed(Algorithm),
    /// Calibrate on the scene and pick algorithm, denoiser and samples per pixel.
    Auto,
}

impl ValueEnum for AlgoArg {
    fn value_variants<'a>() -> &'a [Self] {
        &[
            AlgoArg::Fixed(Algorithm::PathTracing),
            AlgoArg::Fixed(Algorithm::Bidirectional),
            AlgoArg::Fixed(Algorithm::PathTracingWavefront),
            AlgoArg::Fixed(Algorithm::PathTracingWavefrontBinned),
            AlgoArg::Auto,
        ]
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        match self {
            AlgoArg::Fixed(algorithm) => algorithm.to_possible_value(),
            AlgoArg::Auto => Some(PossibleValue::new("auto").help(
                "Measure the configurations on the scene and pick one for --quality or \
                 --budget-ms (--denoise and --spp, when given, stay fixed)",
            )),
        }
    }
}

/// The options of `--algo auto`.
#[derive(Debug, Args)]
pub struct AutoOptions {
    /// With `--algo auto`: the largest acceptable error of a frame (in --quality-metric); the
    /// cheapest configuration reaching it is chosen.
    #[arg(long, conflicts_with = "budget_ms", value_parser = finite_f64(0.0, 1e9))]
    pub quality: Option<f64>,
    /// With `--algo auto`: milliseconds of GPU time per frame; the most accurate configuration
    /// within them is chosen (the default, at 1000/60 ms, without --quality).
    #[arg(long, value_parser = finite_f64(1e-3, 1e9))]
    pub budget_ms: Option<f64>,
    /// With `--algo auto`: the error --quality is in and --budget-ms minimises.
    #[arg(long, value_enum, default_value_t = Metric::Dssim)]
    pub quality_metric: Metric,
    /// With `--algo auto`: frames each candidate renders (accumulation off, the still camera
    /// letting the denoisers' histories build up); its error is that of the last.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub calibration_frames: u32,
    /// With `--algo auto`: samples per pixel of the path-traced reference.
    #[arg(long, default_value = "256", value_parser = samples_per_pixel(u32::MAX.into()))]
    pub calibration_reference_spp: SamplesPerPixel,
}

impl AutoOptions {
    /// An error when a goal is given without `--algo auto` (it would be ignored).
    pub fn check(&self, algo: AlgoArg) -> anyhow::Result<()> {
        if algo != AlgoArg::Auto && (self.quality.is_some() || self.budget_ms.is_some()) {
            anyhow::bail!(
                "--quality and --budget-ms choose a configuration with --algo auto: add --algo auto"
            );
        }
        Ok(())
    }

    /// The goal: `--quality`, else `--budget-ms`, else [`DEFAULT_BUDGET_MS`].
    pub fn goal(&self) -> Goal {
        let metric = self.quality_metric;
        match self.quality {
            Some(target) => Goal::Quality { metric, target },
            None => Goal::Budget {
                metric,
                ms: self.budget_ms.unwrap_or(DEFAULT_BUDGET_MS),
            },
        }
    }

    /// Calibrates `renderer` (candidates: both algorithms, `denoiser` or every denoiser, `spp` or
    /// 1, 2 and 4 samples per pixel), prints the measurements and the choice to stderr, and
    /// switches the renderer to the choice.
    pub fn calibrate(
        &self,
        renderer: &mut Renderer,
        denoiser: Option<Denoiser>,
        spp: Option<SamplesPerPixel>,
    ) -> anyhow::Result<Choice> {
        let defaults = CalibrationOptions::default();
        let options = CalibrationOptions {
            denoisers: denoiser.map_or(defaults.denoisers.clone(), |d| vec![d]),
            spp: spp.map_or(defaults.spp.clone(), |s| vec![s]),
            frames: self.calibration_frames,
            reference_spp: self.calibration_reference_spp,
            ..defaults
        };
        let candidates = options.algorithms.len() * options.denoisers.len() * options.spp.len();
        let (w, h) = renderer.size();
        eprintln!(
            "auto: calibrating {candidates} configurations on {} at {w}x{h} \
             ({} frames each, against a {}-sample reference)",
            renderer.scene().name,
            options.frames,
            options.reference_spp
        );
        let progress = Progress::new(options.total_frames(candidates), "calibration frames");
        let calibration = calibrate(renderer, &options, &mut || progress.inc())?;
        progress.finish();
        let goal = self.goal();
        let choice = calibration.choose(goal)?;
        eprint!("{}", table(&calibration, goal.metric()));
        eprintln!(
            "auto: {} for {} (calibrated in {:.1} s): {}",
            choice.config.name(),
            goal.describe(),
            calibration.seconds,
            choice.reason
        );
        renderer.set_settings(choice.config.apply(*renderer.settings()))?;
        Ok(choice)
    }
}

/// The calibration's measurements, one line per candidate, `*` on the Pareto front of `metric`.
pub fn table(calibration: &Calibration, metric: Metric) -> String {
    let front = calibration.front(metric);
    let mut out = String::new();
    for note in &calibration.notes {
        let _ = writeln!(out, "note: {note}");
    }
    let _ = writeln!(
        out,
        "{:<16} {:>10} {:>10} {:>10} {:>10}",
        "config", "ms/frame", "dssim", "flip", "rel_mse"
    );
    for (i, result) in calibration.results.iter().enumerate() {
        let value = |m: Metric| result.last().map_or(f64::NAN, |row| m.of(row));
        let _ = writeln!(
            out,
            "{:<16} {:>10.3} {:>10.4} {:>10.4} {:>10.4}{}",
            result.config.name(),
            result.ms_per_frame(),
            value(Metric::Dssim),
            value(Metric::Flip),
            value(Metric::RelMse),
            if front.contains(&i) { " *" } else { "" }
        );
    }
    let _ = writeln!(
        out,
        "* on the Pareto front of {} per frame and {}",
        calibration.clock.label(),
        metric.label()
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_is_an_algorithm_on_the_command_line() {
        assert_eq!(AlgoArg::from_str("auto", false), Ok(AlgoArg::Auto));
        assert_eq!(
            AlgoArg::from_str("bdpt", false),
            Ok(AlgoArg::Fixed(Algorithm::Bidirectional))
        );
        assert!(AlgoArg::from_str("mlt", true).is_err());
    }
}
