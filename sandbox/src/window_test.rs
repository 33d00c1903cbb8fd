//! `lucid view --window-test`: a self-test of the window's presentation in a real window. Over the
//! first frames it shrinks the window to a tiny size, reports it minimized (a zero size, as window
//! systems do), restores it, and reports its surface lost; the session prints each step, and the
//! app must keep running and end cleanly.

use super::session::Session;
use winit::dpi::PhysicalSize;

/// The size the window is shrunk to.
pub const TINY: [u32; 2] = [96, 64];
/// Frames skipped while the window is reported minimized.
pub const MINIMIZED_FRAMES: u32 = 5;
/// Frames presented between steps.
const FRAMES_BETWEEN: u64 = 2;

/// What the session does at a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// Ask the window system for [`TINY`].
    Shrink,
    /// Report a zero size, as for a minimized window.
    Minimize,
    /// Ask for the original size again.
    Restore([u32; 2]),
    /// Report the surface lost.
    LoseSurface,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stage {
    Shrink,
    Minimize,
    Restore { shrunk: [u32; 2], skipped: u32 },
    LoseSurface { shrunk: [u32; 2] },
    Done,
}

/// Where the self-test is. Each step waits until the window system has carried out the one before
/// (its resize events arrive when they arrive) and some frames were presented since.
#[derive(Clone, Debug)]
pub struct WindowTest {
    stage: Stage,
    since: u64,
    original: [u32; 2],
}

impl WindowTest {
    /// A test of a window of `original` size.
    pub fn new(original: [u32; 2]) -> Self {
        Self {
            stage: Stage::Shrink,
            since: 0,
            original,
        }
    }

    /// Before a frame, with `presented` frames presented so far and the window's `size` as last
    /// reported (zero when minimized): the step to take now, if any.
    pub fn next(&mut self, presented: u64, size: [u32; 2]) -> Option<Step> {
        let waited = presented >= self.since + FRAMES_BETWEEN;
        let minimized = size.contains(&0);
        let (stage, step) = match self.stage {
            Stage::Shrink if waited => (Stage::Minimize, Step::Shrink),
            Stage::Minimize if waited && !minimized && size != self.original => (
                Stage::Restore {
                    shrunk: size,
                    skipped: 0,
                },
                Step::Minimize,
            ),
            Stage::Restore { shrunk, skipped } if minimized => {
                if skipped + 1 < MINIMIZED_FRAMES {
                    self.stage = Stage::Restore {
                        shrunk,
                        skipped: skipped + 1,
                    };
                    return None;
                }
                (Stage::LoseSurface { shrunk }, Step::Restore(self.original))
            }
            Stage::LoseSurface { shrunk } if waited && !minimized && size != shrunk => {
                (Stage::Done, Step::LoseSurface)
            }
            _ => return None,
        };
        self.stage = stage;
        self.since = presented;
        Some(step)
    }

    /// Whether every step was taken.
    pub fn is_done(&self) -> bool {
        self.stage == Stage::Done
    }
}

impl Session {
    /// Takes the window test's next step, if it is time for one, and prints it.
    pub(super) fn window_test_step(&mut self) -> anyhow::Result<()> {
        let presented = self.frames_presented;
        let reported = self.presenter.size();
        let Some(step) = self
            .window_test
            .as_mut()
            .and_then(|t| t.next(presented, reported))
        else {
            return Ok(());
        };
        match step {
            Step::Shrink => {
                let [w, h] = TINY;
                let _ = self.window.request_inner_size(PhysicalSize::new(w, h));
                eprintln!("window test: frame {presented}: asked for {w}x{h}");
            }
            Step::Minimize => {
                self.presenter.resized([0, 0]);
                let [w, h] = reported;
                eprintln!("window test: frame {presented}: minimized at {w}x{h}");
            }
            Step::Restore([w, h]) => {
                let _ = self.window.request_inner_size(PhysicalSize::new(w, h));
                let now = self.window.inner_size();
                self.presenter.resized([now.width, now.height]);
                eprintln!(
                    "window test: frame {presented}: restored after {MINIMIZED_FRAMES} skipped \
                     frames, asked for {w}x{h}"
                );
            }
            Step::LoseSurface => {
                self.presenter.report_surface_lost()?;
                eprintln!("window test: frame {presented}: surface lost");
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_wait_for_frames_and_for_the_window_system() {
        let original = [640, 360];
        let mut test = WindowTest::new(original);
        assert_eq!(test.next(1, original), None);
        assert_eq!(test.next(2, original), Some(Step::Shrink));
        assert_eq!(test.next(4, original), None, "the resize has not arrived");
        assert_eq!(test.next(5, TINY), Some(Step::Minimize));
        assert_eq!(test.next(5, TINY), None, "waits for the zero size");
        for _ in 1..MINIMIZED_FRAMES {
            assert_eq!(test.next(5, [0, 0]), None);
        }
        assert_eq!(test.next(5, [0, 0]), Some(Step::Restore(original)));
        assert_eq!(
            test.next(8, TINY),
            None,
            "the restoring resize has not arrived"
        );
        assert!(!test.is_done());
        assert_eq!(test.next(8, original), Some(Step::LoseSurface));
        assert!(test.is_done());
        assert_eq!(test.next(100, [0, 0]), None);
    }
}
