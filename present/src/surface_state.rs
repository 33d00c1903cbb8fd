//! What the window's swapchain needs, decided from plain data so that it can be tested without a
//! GPU: a zero-size (minimized) window skips frames and leaves the swapchain alone until it has a
//! size again; resizes and out-of-date or suboptimal reports recreate the swapchain; a lost surface
//! is made anew, and one lost again and again is an error.

use crate::vk_error;
use ash::vk;

/// Surface losses in a row (with no frame presented in between) before the app gives up.
pub const MAX_SURFACE_LOSSES: u32 = 3;

/// What to do before drawing a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prepare {
    /// Nothing to draw on (zero-size window): skip the frame, leave the swapchain as it is.
    Skip,
    /// Recreate the swapchain for the window's size, after making a new surface when `surface`.
    Recreate {
        /// The surface was lost and must be made anew first.
        surface: bool,
    },
    /// Draw with the swapchain as it is.
    Draw,
}

/// The window's size as last reported and what its swapchain needs.
#[derive(Clone, Debug)]
pub struct SurfaceState {
    size: [u32; 2],
    stale: bool,
    surface_lost: bool,
    losses_in_a_row: u32,
}

impl SurfaceState {
    /// The state for a window of `size` whose swapchain was just made for it.
    pub fn new(size: [u32; 2]) -> Self {
        Self {
            size,
            stale: false,
            surface_lost: false,
            losses_in_a_row: 0,
        }
    }

    /// The window now has `size` (a resize, a scale change, or a minimization to zero).
    pub fn resized(&mut self, size: [u32; 2]) {
        self.size = size;
        self.stale = true;
    }

    /// The window's size as last reported.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// Whether the window has no pixels (minimized).
    pub fn is_minimized(&self) -> bool {
        self.size[0] == 0 || self.size[1] == 0
    }

    /// What to do before a frame, given whether the swapchain has images (`usable`).
    pub fn prepare(&self, usable: bool) -> Prepare {
        if self.is_minimized() {
            Prepare::Skip
        } else if self.stale || self.surface_lost || !usable {
            Prepare::Recreate {
                surface: self.surface_lost,
            }
        } else {
            Prepare::Draw
        }
    }

    /// The swapchain was recreated as [`Prepare::Recreate`] asked (it may still have no images when
    /// the surface reports a zero size; the next frame tries again).
    pub fn recreated(&mut self) {
        self.stale = false;
        self.surface_lost = false;
    }

    /// Acts on what acquiring an image returned: `Some(index)` to draw on, `None` to skip this
    /// frame (the swapchain is recreated first when it must be).
    pub fn acquired(
        &mut self,
        result: Result<(u32, bool), vk::Result>,
    ) -> anyhow::Result<Option<u32>> {
        match result {
            Ok((index, suboptimal)) => {
                self.stale |= suboptimal;
                Ok(Some(index))
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => {
                self.stale = true;
                Ok(None)
            }
            Err(vk::Result::TIMEOUT | vk::Result::NOT_READY) => Ok(None),
            Err(vk::Result::ERROR_SURFACE_LOST_KHR) => self.lost().map(|()| None),
            Err(e) => Err(vk_error("vkAcquireNextImageKHR")(e).into()),
        }
    }

    /// Acts on what presenting returned.
    pub fn presented(&mut self, result: Result<bool, vk::Result>) -> anyhow::Result<()> {
        match result {
            Ok(suboptimal) => {
                self.stale |= suboptimal;
                self.losses_in_a_row = 0;
                Ok(())
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => {
                self.stale = true;
                Ok(())
            }
            Err(vk::Result::ERROR_SURFACE_LOST_KHR) => self.lost(),
            Err(e) => Err(vk_error("vkQueuePresentKHR")(e).into()),
        }
    }

    /// A frame could not be drawn after its image was acquired: recreate before the next one.
    pub fn frame_failed(&mut self) {
        self.stale = true;
    }

    /// The window system reported the surface lost: make a new one before the next frame.
    pub fn lost(&mut self) -> anyhow::Result<()> {
        self.surface_lost = true;
        self.losses_in_a_row += 1;
        anyhow::ensure!(
            self.losses_in_a_row <= MAX_SURFACE_LOSSES,
            "the window surface was lost {} times in a row",
            self.losses_in_a_row
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zero_size_window_skips_frames_without_recreating_until_it_has_a_size() {
        let mut state = SurfaceState::new([640, 480]);
        assert_eq!(state.prepare(true), Prepare::Draw);
        state.resized([0, 0]);
        assert!(state.is_minimized());
        for usable in [true, false] {
            assert_eq!(state.prepare(usable), Prepare::Skip);
        }
        state.resized([640, 0]);
        assert_eq!(state.prepare(true), Prepare::Skip);
        state.resized([800, 600]);
        assert_eq!(state.prepare(true), Prepare::Recreate { surface: false });
        state.recreated();
        assert_eq!(state.prepare(true), Prepare::Draw);
        assert_eq!(state.size(), [800, 600]);
    }

    #[test]
    fn a_swapchain_without_images_is_recreated_while_the_window_has_a_size() {
        let mut state = SurfaceState::new([640, 480]);
        assert_eq!(state.prepare(false), Prepare::Recreate { surface: false });
        state.recreated();
        assert_eq!(state.prepare(false), Prepare::Recreate { surface: false });
    }

    #[test]
    fn out_of_date_and_suboptimal_swapchains_are_recreated() {
        let mut state = SurfaceState::new([64, 64]);
        assert_eq!(state.acquired(Ok((2, false))).unwrap(), Some(2));
        assert_eq!(state.prepare(true), Prepare::Draw);

        assert_eq!(
            state.acquired(Ok((1, true))).unwrap(),
            Some(1),
            "draw, then recreate"
        );
        assert_eq!(state.prepare(true), Prepare::Recreate { surface: false });
        state.recreated();

        let out_of_date = Err(vk::Result::ERROR_OUT_OF_DATE_KHR);
        assert_eq!(state.acquired(out_of_date).unwrap(), None);
        assert_eq!(state.prepare(true), Prepare::Recreate { surface: false });
        state.recreated();

        state.presented(Ok(true)).unwrap();
        assert_eq!(state.prepare(true), Prepare::Recreate { surface: false });
        state.recreated();
        state
            .presented(Err(vk::Result::ERROR_OUT_OF_DATE_KHR))
            .unwrap();
        assert_eq!(state.prepare(true), Prepare::Recreate { surface: false });
        state.recreated();

        assert_eq!(state.acquired(Err(vk::Result::TIMEOUT)).unwrap(), None);
        assert_eq!(state.prepare(true), Prepare::Draw, "a timeout just retries");
        state.frame_failed();
        assert_eq!(state.prepare(true), Prepare::Recreate { surface: false });
    }

    #[test]
    fn a_lost_surface_is_made_anew_and_repeated_losses_are_an_error() {
        let mut state = SurfaceState::new([64, 64]);
        let lost = vk::Result::ERROR_SURFACE_LOST_KHR;
        assert_eq!(state.acquired(Err(lost)).unwrap(), None);
        assert_eq!(state.prepare(true), Prepare::Recreate { surface: true });
        state.recreated();
        assert_eq!(state.prepare(true), Prepare::Draw);

        state.presented(Err(lost)).unwrap();
        assert_eq!(state.prepare(true), Prepare::Recreate { surface: true });
        state.recreated();
        state.presented(Ok(false)).unwrap();

        for _ in 0..MAX_SURFACE_LOSSES {
            assert_eq!(state.acquired(Err(lost)).unwrap(), None);
            state.recreated();
        }
        let error = state.acquired(Err(lost)).unwrap_err().to_string();
        assert!(error.contains("lost 4 times in a row"), "{error}");
    }

    #[test]
    fn other_errors_are_reported_not_swallowed() {
        let mut state = SurfaceState::new([64, 64]);
        let error = state
            .acquired(Err(vk::Result::ERROR_DEVICE_LOST))
            .unwrap_err()
            .to_string();
        assert!(error.contains("vkAcquireNextImageKHR"), "{error}");
        assert!(error.contains("the GPU device was lost"), "{error}");
        let error = state
            .presented(Err(vk::Result::ERROR_OUT_OF_HOST_MEMORY))
            .unwrap_err()
            .to_string();
        assert!(error.contains("vkQueuePresentKHR"), "{error}");
    }
}
