//! Device loss: once any Vulkan call reports `VK_ERROR_DEVICE_LOST`, every later submission and
//! wait of the context fails with [`EngineError::DeviceLost`] at once. A fault can be injected
//! (the `LUCID_INJECT_DEVICE_LOST` variable, [`super::ContextDesc::inject_device_lost_at_frame`]):
//! the N-th frame's submission then reports device loss instead of running, so that what an
//! application does on a real loss can be tested on any device.

use crate::error::EngineError;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// Whether the device was lost, and the injected fault, if any.
#[derive(Debug, Default)]
pub(crate) struct DeviceLoss {
    lost: AtomicBool,
    injected: AtomicBool,
    /// 1-based index of the frame submission that reports device loss.
    inject_at_frame: Option<u64>,
    frames_submitted: AtomicU64,
}

impl DeviceLoss {
    /// Tracks loss; the frame submission `inject_at_frame` (1-based) reports it.
    pub fn new(inject_at_frame: Option<u64>) -> Self {
        Self {
            inject_at_frame,
            ..Self::default()
        }
    }

    /// Whether the device was lost (or a loss was injected).
    pub fn is_lost(&self) -> bool {
        self.lost.load(Ordering::Acquire)
    }

    /// Counts a frame submission; true when this one is the injected fault (the device counts as
    /// lost from now on).
    pub fn frame_submitted(&self) -> bool {
        let index = self.frames_submitted.fetch_add(1, Ordering::AcqRel) + 1;
        let inject = self.inject_at_frame == Some(index);
        if inject {
            self.injected.store(true, Ordering::Release);
            self.lost.store(true, Ordering::Release);
        }
        inject
    }

    /// Marks the device lost when `error` says so; returns the error.
    pub fn observe(&self, error: EngineError) -> EngineError {
        if matches!(error, EngineError::DeviceLost { .. }) {
            self.lost.store(true, Ordering::Release);
        }
        error
    }

    /// The error of a call made after the loss, `during` what.
    pub fn error(&self, during: impl Into<String>) -> EngineError {
        let during = during.into();
        EngineError::DeviceLost {
            during: if self.injected.load(Ordering::Acquire) {
                format!("{during} (an injected fault: LUCID_INJECT_DEVICE_LOST)")
            } else {
                during
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::DeviceLoss;
    use crate::error::EngineError;

    #[test]
    fn the_chosen_frame_loses_the_device_for_good() {
        let loss = DeviceLoss::new(Some(2));
        assert!(!loss.frame_submitted());
        assert!(!loss.is_lost());
        assert!(loss.frame_submitted());
        assert!(loss.is_lost());
        assert!(!loss.frame_submitted());
        assert!(loss.is_lost());
        assert!(loss.error("frame 2").to_string().contains("injected"));
    }

    #[test]
    fn a_reported_loss_is_remembered() {
        let loss = DeviceLoss::new(None);
        let other = loss.observe(EngineError::InvalidArgument("x".into()));
        assert!(matches!(other, EngineError::InvalidArgument(_)));
        assert!(!loss.is_lost());
        loss.observe(EngineError::DeviceLost {
            during: "vkWaitSemaphores".into(),
        });
        assert!(loss.is_lost());
        assert!(!loss.error("frame 9").to_string().contains("injected"));
    }
}
