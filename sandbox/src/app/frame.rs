//! One frame of the window: recreate the swapchain when needed, acquire, run the UI, build the
//! render graph (frame source, tone mapping, UI, present), submit, present, and deliver what
//! earlier frames read back.

use super::compose::{self, Extras, Target};
use super::frame_source::FrameRequest;
use super::gpu::Acquired;
use super::pending::{CaptureJob, Pending};
use super::session::{Flow, Session};
use super::{capture, ui};
use anyhow::Context as _;
use lucid_engine::graph::{RenderGraph, SubmitOptions};
use std::time::{SystemTime, UNIX_EPOCH};

/// Frames that may fail in a row before the app gives up.
const MAX_FAILURES_IN_A_ROW: u32 = 3;

/// Seconds between checks of the shader sources.
const SHADER_CHECK_INTERVAL: f64 = 0.5;

impl Session {
    /// Recompiles shaders edited on disk; a compile error is shown and the old pipelines stay.
    fn reload_shaders(&mut self, now: f64) {
        if now - self.last_shader_check < SHADER_CHECK_INTERVAL
            || !self.shader_watcher.is_available()
        {
            return;
        }
        self.last_shader_check = now;
        let library = self.source.executor().library();
        match self.shader_watcher.poll(library) {
            Some(lucid_passes::hot_reload::Reload::Reloaded(n)) => {
                self.state.message = Some(format!("reloaded {n} shaders"));
            }
            Some(lucid_passes::hot_reload::Reload::Failed(error)) => {
                self.state.message =
                    Some(format!("shader error (previous shaders kept):\n{error}"));
            }
            None => {}
        }
    }

    /// Draws and presents one frame (nothing while minimized).
    pub fn redraw(&mut self) -> anyhow::Result<Flow> {
        let now = self.clock.elapsed().as_secs_f64();
        let dt = now - self.last_frame;
        self.last_frame = now;
        self.update_camera(now, dt);
        self.reload_shaders(now);
        if self.needs_recreate || !self.swapchain.is_usable() {
            self.recreate()?;
        }
        if !self.swapchain.is_usable() {
            return Ok(Flow::Continue);
        }
        if let Some((outputs, pending)) = self.ring.wait_next(self.source.executor())? {
            self.deliver(pending.finish(&outputs)?);
        }
        let index = match self
            .swapchain
            .acquire(self.ring.acquire_semaphore(), &self.window)?
        {
            Acquired::Image { index, suboptimal } => {
                self.needs_recreate |= suboptimal;
                index
            }
            Acquired::OutOfDate => {
                self.needs_recreate = true;
                return Ok(self.flow());
            }
            Acquired::NotReady => return Ok(self.flow()),
        };
        let reads_back = match self.submit(index, now) {
            Ok(reads_back) => {
                self.failures_in_a_row = 0;
                reads_back
            }
            Err(e) => {
                self.ring.consume_acquire()?;
                self.ctx.wait_idle()?;
                self.needs_recreate = true;
                self.failures_in_a_row += 1;
                if self.failures_in_a_row >= MAX_FAILURES_IN_A_ROW {
                    return Err(e.context("rendering failed repeatedly"));
                }
                self.state.message = Some(format!("frame failed: {e:#}"));
                return Ok(self.flow());
            }
        };
        if self.swapchain.present(index, &self.window)? {
            self.needs_recreate = true;
        }
        self.frames_presented += 1;
        self.stats.push(now, dt);
        if reads_back {
            // The executor drops the outputs of earlier frames when a later frame's graph has a
            // different plan, so a frame with readbacks is waited for at once.
            self.finish_all()?;
        }
        Ok(self.flow())
    }

    fn flow(&self) -> Flow {
        if self.exit {
            Flow::Exit
        } else {
            Flow::Continue
        }
    }

    pub(super) fn deliver(&mut self, finished: super::pending::Finished) {
        if let Some(message) = finished.message {
            self.state.message = Some(message);
        }
        self.exit |= finished.screenshot_written;
    }

    /// Waits for every frame in flight and delivers what they read back.
    fn finish_all(&mut self) -> anyhow::Result<()> {
        for (outputs, pending) in self.ring.drain(self.source.executor())? {
            self.deliver(pending.finish(&outputs)?);
        }
        Ok(())
    }

    /// Recreates the swapchain and the UI framebuffers for the window's size.
    fn recreate(&mut self) -> anyhow::Result<()> {
        self.finish_all()?;
        self.ctx.wait_idle()?;
        let size = self.window.inner_size();
        self.swapchain
            .recreate([size.width, size.height])
            .context("recreating the swapchain")?;
        if self.swapchain.is_usable() {
            self.overlay.set_targets(
                self.swapchain.format(),
                self.swapchain.views(),
                self.swapchain.extent(),
            )?;
        }
        self.needs_recreate = false;
        Ok(())
    }

    /// Runs the UI, records and submits the frame for swapchain image `index`; returns whether it
    /// reads anything back.
    fn submit(&mut self, index: u32, now: f64) -> anyhow::Result<bool> {
        let extent = self.swapchain.extent();
        let size = [extent.width, extent.height];
        let memory = self.ctx.memory_report();
        let pass_timings = self.source.executor().pass_timings().to_vec();
        let readouts = ui::Readouts {
            fps: self.stats.fps(now),
            frame_times_ms: self.stats.frame_times_ms().collect(),
            pass_timings: &pass_timings,
            samples: self.source.samples_accumulated(),
            memory,
            source: self.source.name(),
            device: &self.ctx.info().name,
            extent: size,
            split: self.source.split_stats(),
        };
        let state = &mut self.state;
        let mut requests = ui::Requests::default();
        let overlay_frame = self.overlay.run(&self.window, |ctx| {
            requests = ui::draw(ctx, state, &readouts)
        })?;
        self.handle_requests(requests, now);

        let mut pending = Pending::default();
        let frame_number = self.frames_presented + 1;
        if let Some(shot) = &self.options.screenshot {
            if shot.after_frames.max(1) == frame_number {
                pending.screenshot = Some(shot.path.clone());
            }
        }
        if std::mem::take(&mut self.capture_requested) {
            let seconds = SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_secs());
            pending.capture = Some(CaptureJob {
                dir: self.options.capture_dir.clone(),
                stem: capture::capture_stem(seconds, frame_number),
                display: self.state.display,
            });
        }
        let extras = Extras {
            capture_hdr: pending.capture.is_some(),
            screenshot: pending.screenshot.is_some(),
        };

        let camera = self.state.camera.pose.camera();
        let request = FrameRequest {
            camera: &camera,
            settings: &self.state.render,
            extent: size,
            time: now as f32,
            split: self.state.split.as_ref(),
        };
        let mut graph = RenderGraph::new();
        let hdr = match self.source.render(&mut graph, &request) {
            Ok(hdr) => Some(hdr),
            Err(e) => {
                self.state.message = Some(format!("{} failed: {e:#}", self.source.name()));
                graph = RenderGraph::new();
                None
            }
        };
        let image = &self.swapchain.images()[index as usize];
        let target = || Target { image, index };
        let display = self.state.display;
        pending.readbacks = compose::add(
            &mut graph,
            hdr,
            target(),
            &self.overlay,
            overlay_frame.clone(),
            &display,
            extras,
        )?;
        let compiled = match graph.compile() {
            Ok(compiled) => compiled,
            Err(e) if hdr.is_some() => {
                self.state.message = Some(format!("{} failed: {e}", self.source.name()));
                let mut fallback = RenderGraph::new();
                pending.readbacks = compose::add(
                    &mut fallback,
                    None,
                    target(),
                    &self.overlay,
                    overlay_frame,
                    &display,
                    extras,
                )?;
                fallback.compile()?
            }
            Err(e) => return Err(e.into()),
        };
        let submit = SubmitOptions {
            wait: vec![(self.ring.acquire_semaphore(), compose::acquire_wait_stage())],
            signal: vec![self.swapchain.render_finished(index)],
        };
        let frame = self.source.executor().execute_with(compiled, &submit)?;
        let reads_back = pending.capture.is_some() || pending.screenshot.is_some();
        self.ring.submitted(frame, pending);
        Ok(reads_back)
    }
}
