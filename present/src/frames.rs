//! The app's frames in flight: one acquire semaphore per frame, and what each submitted frame
//! still owes the app (its outputs, and the payload saying what to do with them).

use crate::vk_error;
use ash::vk;
use lucid_engine::graph::{Executor, FrameId, FrameOutputs};
use lucid_engine::Context;

struct Slot<T> {
    acquire: vk::Semaphore,
    in_flight: Option<(FrameId, T)>,
}

/// A ring of as many frames as the executor keeps in flight.
pub struct FrameRing<T> {
    slots: Vec<Slot<T>>,
    next: usize,
    ctx: Context,
}

impl<T> FrameRing<T> {
    /// A ring of `ctx.frames_in_flight()` slots.
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let mut ring = Self {
            slots: Vec::new(),
            next: 0,
            ctx: ctx.clone(),
        };
        for _ in 0..ctx.frames_in_flight() {
            let acquire = ring.semaphore()?;
            ring.slots.push(Slot {
                acquire,
                in_flight: None,
            });
        }
        Ok(ring)
    }

    fn semaphore(&self) -> anyhow::Result<vk::Semaphore> {
        // SAFETY: device valid.
        let semaphore = unsafe {
            self.ctx
                .device()
                .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
        }
        .map_err(vk_error("vkCreateSemaphore"))?;
        self.ctx.set_name(semaphore, "image acquired");
        Ok(semaphore)
    }

    /// Waits for the frame that last used the next slot and returns its outputs and payload; the
    /// slot's acquire semaphore is then free to use.
    pub fn wait_next(
        &mut self,
        executor: &mut Executor,
    ) -> anyhow::Result<Option<(FrameOutputs, T)>> {
        let slot = &mut self.slots[self.next];
        match slot.in_flight.take() {
            Some((frame, payload)) => Ok(Some((executor.wait(frame)?, payload))),
            None => Ok(None),
        }
    }

    /// The acquire semaphore of the next slot.
    pub fn acquire_semaphore(&self) -> vk::Semaphore {
        self.slots[self.next].acquire
    }

    /// Records that `frame` was submitted in the next slot, and moves on.
    pub fn submitted(&mut self, frame: FrameId, payload: T) {
        self.slots[self.next].in_flight = Some((frame, payload));
        self.next = (self.next + 1) % self.slots.len();
    }

    /// Unsignals the next slot's acquire semaphore after an image was acquired but no frame was
    /// submitted to wait on it (an empty submission waits on it).
    pub fn consume_acquire(&self) -> anyhow::Result<()> {
        let waits = [vk::SemaphoreSubmitInfo::default()
            .semaphore(self.acquire_semaphore())
            .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
        let submit = [vk::SubmitInfo2::default().wait_semaphore_infos(&waits)];
        self.ctx.submit(&submit, vk::Fence::null())?;
        Ok(())
    }

    /// Waits for every frame in flight; returns their outputs and payloads, oldest first.
    pub fn drain(&mut self, executor: &mut Executor) -> anyhow::Result<Vec<(FrameOutputs, T)>> {
        let mut done = Vec::new();
        for _ in 0..self.slots.len() {
            if let Some(frame) = self.wait_next(executor)? {
                done.push(frame);
            }
            self.next = (self.next + 1) % self.slots.len();
        }
        Ok(done)
    }
}

impl<T> Drop for FrameRing<T> {
    fn drop(&mut self) {
        if let Err(e) = self.ctx.wait_idle() {
            tracing::error!("waiting for the GPU before destroying semaphores: {e}");
        }
        for slot in &self.slots {
            // SAFETY: the GPU is idle; nothing waits on the semaphore.
            unsafe { self.ctx.device().destroy_semaphore(slot.acquire, None) };
        }
    }
}
