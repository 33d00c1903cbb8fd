//! Which denoising a frame gets under an [`SvgfMode`].

use super::params::SvgfMode;
use crate::samples_per_pixel::SamplesPerPixel;
use std::time::Instant;

/// What the denoiser does in one frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Apply {
    /// Full temporal SVGF on the frame's own radiance; `continues`: the previous frame ran it too,
    /// so its histories are last frame's (otherwise they are stale and ignored).
    Temporal {
        /// Whether the previous frame ran temporal SVGF.
        continues: bool,
    },
    /// The spatial filter on the (accumulated) output.
    Spatial,
    /// Nothing: the output passes through.
    Nothing,
}

/// Tracks when accumulation restarted, for [`SvgfMode::AfterSeconds`], and which frame last ran
/// temporal SVGF.
#[derive(Clone, Copy, Debug, Default)]
pub struct Schedule {
    started: Option<Instant>,
    last_temporal: Option<u32>,
}

impl Schedule {
    /// Decides the denoising of frame `frame_index`; `accumulated` frames of `samples_per_pixel`
    /// samples were averaged before this one (0 when accumulation restarts).
    pub fn decide(
        &mut self,
        mode: SvgfMode,
        frame_index: u32,
        accumulated: u32,
        samples_per_pixel: SamplesPerPixel,
    ) -> Apply {
        if accumulated == 0 || self.started.is_none() {
            self.started = Some(Instant::now());
        }
        let samples = u64::from(accumulated + 1) * u64::from(samples_per_pixel.get());
        let spatial_if = |ready: bool| {
            if ready {
                Apply::Spatial
            } else {
                Apply::Nothing
            }
        };
        match mode {
            SvgfMode::Temporal => {
                let previous = self.last_temporal.replace(frame_index);
                Apply::Temporal {
                    // The same index again is a frame planned but not rendered (`frame_plan`).
                    continues: previous.is_some_and(|p| frame_index.wrapping_sub(p) <= 1),
                }
            }
            SvgfMode::EveryFrame => Apply::Spatial,
            SvgfMode::AfterSamples(n) => spatial_if(samples >= u64::from(n)),
            SvgfMode::AfterSeconds(s) => {
                spatial_if(self.started.is_some_and(|t| t.elapsed().as_secs_f32() >= s))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ONE: SamplesPerPixel = SamplesPerPixel::ONE;
    const FOUR: SamplesPerPixel = SamplesPerPixel::new(4).unwrap();

    #[test]
    fn sample_budget_waits_for_enough_samples() {
        let mut s = Schedule::default();
        let mode = SvgfMode::AfterSamples(8);
        assert_eq!(s.decide(mode, 0, 0, FOUR), Apply::Nothing);
        assert_eq!(s.decide(mode, 1, 1, FOUR), Apply::Spatial);
        assert_eq!(s.decide(mode, 2, 0, FOUR), Apply::Nothing);
    }

    #[test]
    fn time_budget_restarts_with_accumulation() {
        let mut s = Schedule::default();
        assert_eq!(
            s.decide(SvgfMode::AfterSeconds(60.0), 0, 0, ONE),
            Apply::Nothing
        );
        assert_eq!(
            s.decide(SvgfMode::AfterSeconds(0.0), 1, 3, ONE),
            Apply::Spatial
        );
    }

    #[test]
    fn temporal_history_continues_only_from_the_previous_frame() {
        let mut s = Schedule::default();
        let temporal = |continues| Apply::Temporal { continues };
        assert_eq!(s.decide(SvgfMode::Temporal, 5, 0, ONE), temporal(false));
        assert_eq!(s.decide(SvgfMode::Temporal, 6, 0, ONE), temporal(true));
        assert_eq!(s.decide(SvgfMode::EveryFrame, 7, 0, ONE), Apply::Spatial);
        assert_eq!(s.decide(SvgfMode::Temporal, 8, 0, ONE), temporal(false));
    }
}
