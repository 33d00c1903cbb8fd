//! One frame of the window: let the presenter prepare the swapchain and acquire an image, run the
//! UI, build the render graph (frame source, tone mapping, UI, present), submit and present, and
//! deliver what earlier frames read back.

use super::compose::{self, Extras};
use super::frame_source::FrameRequest;
use super::pending::{CaptureJob, Pending};
use super::session::{Flow, Session};
use super::{capture, ui};
use lucid_engine::graph::{CompiledGraph, RenderGraph};
use lucid_present::PresentTarget;
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
            Some(lucid_passes::plumbing::hot_reload::Reload::Reloaded(n)) => {
                self.state.message = Some(format!("reloaded {n} shaders"));
            }
            Some(lucid_passes::plumbing::hot_reload::Reload::Failed(error)) => {
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
        self.window_test_step()?;
        let began = self.presenter.begin(self.source.executor())?;
        for (outputs, pending) in began.finished {
            self.deliver(pending.finish(&outputs)?);
        }
        let swapchain = self.presenter.swapchain();
        if began.recreated && swapchain.is_usable() {
            self.overlay
                .set_targets(swapchain.format(), swapchain.views(), swapchain.extent())?;
        }
        let Some(target) = began.target else {
            return self.flow();
        };
        let reads_back = match self.submit(target, now) {
            Ok(reads_back) => {
                self.failures_in_a_row = 0;
                reads_back
            }
            Err(e) => {
                self.failures_in_a_row += 1;
                if self.failures_in_a_row >= MAX_FAILURES_IN_A_ROW {
                    return Err(e.context("rendering failed repeatedly"));
                }
                self.state.message = Some(format!("frame failed: {e:#}"));
                return self.flow();
            }
        };
        self.frames_presented += 1;
        self.stats.push(now, dt);
        if reads_back {
            // The executor drops the outputs of earlier frames when a later frame's graph has a
            // different plan, so a frame with readbacks is waited for at once.
            self.finish_all()?;
        }
        self.flow()
    }

    fn flow(&self) -> anyhow::Result<Flow> {
        if !self.exit {
            return Ok(Flow::Continue);
        }
        if let Some(test) = &self.window_test {
            anyhow::ensure!(
                test.is_done(),
                "the window test had not taken every step by the screenshot; take it later"
            );
        }
        Ok(Flow::Exit)
    }

    pub(super) fn deliver(&mut self, finished: super::pending::Finished) {
        if let Some(message) = finished.message {
            self.state.message = Some(message);
        }
        self.exit |= finished.screenshot_written;
    }

    /// Waits for every frame in flight and delivers what they read back.
    pub(super) fn finish_all(&mut self) -> anyhow::Result<()> {
        for (outputs, pending) in self.presenter.finish(self.source.executor())? {
            self.deliver(pending.finish(&outputs)?);
        }
        Ok(())
    }

    /// Records the frame for `target`, submits and presents it; returns whether it reads anything
    /// back. A frame that cannot be recorded gives its image up.
    fn submit(&mut self, target: PresentTarget, now: f64) -> anyhow::Result<bool> {
        match self.record(&target, now) {
            Ok((graph, pending)) => {
                let reads_back = pending.capture.is_some() || pending.screenshot.is_some();
                let executor = self.source.executor();
                self.presenter.submit(executor, target, graph, pending)?;
                Ok(reads_back)
            }
            Err(e) => {
                self.presenter.abandon(target)?;
                Err(e)
            }
        }
    }

    /// Runs the UI and builds the frame's graph for `target`; returns it compiled, with what the
    /// frame must deliver once done.
    fn record(
        &mut self,
        target: &PresentTarget,
        now: f64,
    ) -> anyhow::Result<(CompiledGraph, Pending)> {
        let size = target.extent();
        let memory = self.ctx.memory_report();
        let pass_timings = self.source.executor().pass_timings().to_vec();
        let readouts = ui::Readouts {
            frame_rate: self.stats.frame_rate(now),
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
        let display = self.state.display;
        pending.readbacks = compose::add(
            &mut graph,
            hdr,
            target,
            Some((&self.overlay, overlay_frame.clone())),
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
                    target,
                    Some((&self.overlay, overlay_frame)),
                    &display,
                    extras,
                )?;
                fallback.compile()?
            }
            Err(e) => return Err(e.into()),
        };
        Ok((compiled, pending))
    }
}
