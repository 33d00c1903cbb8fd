//! Progress for long work: a bar on a terminal, plain lines otherwise.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// Reports progress of `total` steps.
pub struct Progress {
    bar: Option<ProgressBar>,
    total: u64,
    done: std::cell::Cell<u64>,
    unit: &'static str,
}

impl Progress {
    /// A progress report of `total` `unit`s.
    pub fn new(total: u64, unit: &'static str) -> Self {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new(total);
            if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} ({eta})") {
                bar.set_style(style);
            }
            bar.set_message(unit);
            bar
        });
        Self {
            bar,
            total,
            done: std::cell::Cell::new(0),
            unit,
        }
    }

    /// One more step done.
    pub fn inc(&self) {
        self.inc_by(1);
    }

    /// `steps` more steps done (work that ended early skips the steps it did not need).
    pub fn inc_by(&self, steps: u64) {
        let before = self.done.get();
        let done = before + steps;
        self.done.set(done);
        match &self.bar {
            Some(bar) => bar.inc(steps),
            None => {
                let step = (self.total / 10).max(1);
                if steps > 0 && done / step > before / step {
                    eprintln!("{done}/{} {}", self.total, self.unit);
                }
            }
        }
    }

    /// All done.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
