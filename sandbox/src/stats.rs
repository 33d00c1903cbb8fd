//! Frame statistics for the panels: frame time and frame rate over the last second (or the last
//! frame, when frames take longer), and a frame-time history for the graph. Times are passed in,
//! so the logic needs no clock.

use std::collections::VecDeque;

/// Frame times kept for the graph.
const HISTORY: usize = 240;
/// The window of the frame-rate figures, in seconds.
const FPS_WINDOW: f64 = 1.0;

/// Frame time and frame rate of recent frames.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameRate {
    /// Mean frame time in milliseconds.
    pub frame_ms: f64,
    /// Standard deviation of the frame time in milliseconds.
    pub frame_ms_std_dev: f64,
    /// Frames per second: the inverse of the mean frame time.
    pub fps: f64,
}

impl FrameRate {
    /// `16.7 ± 0.3 ms a frame, 59.9 FPS`: three significant digits, so slow frames (seconds
    /// each on a CPU device) still read true; `no frames yet` before the first frame.
    pub fn label(&self) -> String {
        if self.fps == 0.0 {
            return "no frames yet".into();
        }
        format!(
            "{} ± {} ms a frame, {} FPS",
            significant(self.frame_ms),
            significant(self.frame_ms_std_dev),
            significant(self.fps)
        )
    }
}

/// `value` with three significant digits (and all of its integer digits).
fn significant(value: f64) -> String {
    let decimals = if value == 0.0 {
        1
    } else {
        (2 - value.abs().log10().floor() as i32).max(0)
    };
    format!("{value:.*}", decimals as usize)
}

/// Collects frame durations.
#[derive(Clone, Debug, Default)]
pub struct FrameStats {
    /// `(end time in seconds, duration in seconds)` of recent frames, oldest first.
    frames: VecDeque<(f64, f64)>,
}

impl FrameStats {
    /// Records a frame that ended at `now` seconds and took `duration` seconds.
    pub fn push(&mut self, now: f64, duration: f64) {
        if duration > 0.0 && duration.is_finite() {
            self.frames.push_back((now, duration));
        }
        while self.frames.len() > HISTORY {
            self.frames.pop_front();
        }
    }

    /// Frame time and rate over the frames that ended in the last second before `now`, or over
    /// the latest frame when none did (a frame took longer than a second).
    pub fn frame_rate(&self, now: f64) -> FrameRate {
        let mut durations: Vec<f64> = self
            .frames
            .iter()
            .filter(|(end, _)| now - end <= FPS_WINDOW)
            .map(|(_, d)| *d)
            .collect();
        if durations.is_empty() {
            durations.extend(self.frames.back().map(|(_, d)| *d));
        }
        if durations.is_empty() {
            return FrameRate::default();
        }
        let n = durations.len() as f64;
        let mean = durations.iter().sum::<f64>() / n;
        let variance = durations.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / n;
        FrameRate {
            frame_ms: mean * 1e3,
            frame_ms_std_dev: variance.sqrt() * 1e3,
            fps: 1.0 / mean,
        }
    }

    /// Recent frame times in milliseconds, oldest first.
    pub fn frame_times_ms(&self) -> impl Iterator<Item = f64> + '_ {
        self.frames.iter().map(|(_, d)| d * 1e3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_rate_covers_the_last_second() {
        let mut stats = FrameStats::default();
        stats.push(0.1, 0.5);
        let mut t = 1.5;
        for d in [0.01, 0.03, 0.01, 0.03] {
            t += d;
            stats.push(t, d);
        }
        let rate = stats.frame_rate(t);
        assert!((rate.frame_ms - 20.0).abs() < 1e-9);
        assert!((rate.frame_ms_std_dev - 10.0).abs() < 1e-9);
        assert!((rate.fps - 50.0).abs() < 1e-9);
        assert_eq!(FrameStats::default().frame_rate(1.0), FrameRate::default());
    }

    #[test]
    fn frames_slower_than_the_window_still_count() {
        let mut stats = FrameStats::default();
        stats.push(2.4, 2.4);
        stats.push(4.8, 2.4);
        let rate = stats.frame_rate(7.0);
        assert!((rate.frame_ms - 2400.0).abs() < 1e-9);
        assert_eq!(rate.label(), "2400 ± 0.0 ms a frame, 0.417 FPS");
    }

    #[test]
    fn labels_keep_three_significant_digits() {
        let label = |frame_ms: f64, frame_ms_std_dev: f64| {
            FrameRate {
                frame_ms,
                frame_ms_std_dev,
                fps: 1e3 / frame_ms,
            }
            .label()
        };
        assert_eq!(label(16.7, 0.31), "16.7 ± 0.310 ms a frame, 59.9 FPS");
        assert_eq!(label(0.25, 0.02), "0.250 ± 0.0200 ms a frame, 4000 FPS");
        assert_eq!(label(125.0, 4.0), "125 ± 4.00 ms a frame, 8.00 FPS");
        assert_eq!(FrameRate::default().label(), "no frames yet");
    }

    #[test]
    fn history_is_bounded_and_ignores_bad_durations() {
        let mut stats = FrameStats::default();
        for i in 0..1000 {
            stats.push(i as f64, 0.016);
        }
        stats.push(1001.0, 0.0);
        stats.push(1002.0, f64::NAN);
        assert_eq!(stats.frame_times_ms().count(), HISTORY);
    }
}
