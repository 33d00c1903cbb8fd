//! Frame statistics for the panels: FPS mean and standard deviation over the last second, and a
//! frame-time history for the graph. Times are passed in, so the logic needs no clock.

use std::collections::VecDeque;

/// Frame times kept for the graph.
const HISTORY: usize = 240;
/// The window of the FPS figures, in seconds.
const FPS_WINDOW: f64 = 1.0;

/// Mean and standard deviation of the frame rate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fps {
    /// Mean frames per second.
    pub mean: f64,
    /// Standard deviation of the per-frame rate.
    pub std_dev: f64,
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

    /// FPS over the frames that ended in the last second before `now`.
    pub fn fps(&self, now: f64) -> Fps {
        let rates: Vec<f64> = self
            .frames
            .iter()
            .filter(|(end, _)| now - end <= FPS_WINDOW)
            .map(|(_, d)| 1.0 / d)
            .collect();
        if rates.is_empty() {
            return Fps::default();
        }
        let n = rates.len() as f64;
        let mean = rates.iter().sum::<f64>() / n;
        let variance = rates.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / n;
        Fps {
            mean,
            std_dev: variance.sqrt(),
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
    fn fps_covers_the_last_second() {
        let mut stats = FrameStats::default();
        stats.push(0.1, 0.5);
        let mut t = 1.5;
        for d in [0.01, 0.02, 0.01, 0.02] {
            t += d;
            stats.push(t, d);
        }
        let fps = stats.fps(t);
        assert!((fps.mean - 75.0).abs() < 1e-9);
        assert!((fps.std_dev - 25.0).abs() < 1e-9);
        assert_eq!(stats.fps(100.0), Fps::default());
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
