//! The sandbox's `--algo auto`: the goal the panel edits and what the last calibration chose.

use lucid_passes::tradeoff::{Choice, Goal, Metric};

/// Which goal the panel's calibration picks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GoalKind {
    /// The cheapest configuration reaching [`AutoState::quality`].
    Quality,
    /// The most accurate configuration within [`AutoState::budget_ms`].
    Budget,
}

/// The panel's calibration goal and last result.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoState {
    /// Quality target or frame budget.
    pub kind: GoalKind,
    /// The largest acceptable error, in `metric`.
    pub quality: f64,
    /// Milliseconds per frame.
    pub budget_ms: f64,
    /// The error the goal is stated in.
    pub metric: Metric,
    /// The last calibration's choice (with its size and duration), or why it failed.
    pub last: Option<Result<Calibrated, String>>,
}

/// What the last calibration chose.
#[derive(Clone, Debug, PartialEq)]
pub struct Calibrated {
    /// The choice and its reason.
    pub choice: Choice,
    /// The goal it was chosen for, in words.
    pub goal: String,
    /// Wall-clock seconds the calibration took.
    pub seconds: f64,
}

impl Default for AutoState {
    /// A 60-frames-per-second budget, least DSSIM.
    fn default() -> Self {
        Self {
            kind: GoalKind::Budget,
            quality: 0.3,
            budget_ms: 1000.0 / 60.0,
            metric: Metric::Dssim,
            last: None,
        }
    }
}

impl AutoState {
    /// The goal the panel describes.
    pub fn goal(&self) -> Goal {
        match self.kind {
            GoalKind::Quality => Goal::Quality {
                metric: self.metric,
                target: self.quality,
            },
            GoalKind::Budget => Goal::Budget {
                metric: self.metric,
                ms: self.budget_ms,
            },
        }
    }
}
