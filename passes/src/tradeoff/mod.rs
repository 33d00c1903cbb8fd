//! Speed against accuracy: measuring configurations (algorithm x denoiser x samples per pixel per
//! frame) of one scene for GPU time and error against a many-sample reference ([`measure`]), their
//! Pareto front ([`pareto`]), and the short calibration behind `--algo auto` that picks the
//! cheapest configuration meeting a quality target or the most accurate within a frame budget
//! ([`calibrate`]). `lucid converge` and `lucid render --algo auto` use it; so can a game:
//!
//! ```no_run
//! # fn demo(renderer: &mut lucid_passes::renderer::Renderer) -> Result<(), lucid_passes::tradeoff::TradeoffError> {
//! use lucid_passes::tradeoff::{calibrate, CalibrationOptions, Goal, Metric};
//! let calibration = calibrate(renderer, &CalibrationOptions::default(), &mut || {})?;
//! let choice = calibration.choose(Goal::Budget { metric: Metric::Dssim, ms: 8.0 })?;
//! println!("{}: {}", choice.config.name(), choice.reason);
//! renderer.set_settings(choice.config.apply(*renderer.settings()))?;
//! # Ok(()) }
//! ```

pub mod calibrate;
mod error;
pub mod measure;
mod metric;
pub mod pareto;

pub use calibrate::{calibrate, Calibration, CalibrationOptions, Choice, Goal};
pub use error::TradeoffError;
pub use measure::{Clock, Config, ConfigResult, Limits, Measurement, Schedule};
pub use metric::Metric;
