//! The winit application handler: creates the session when the event loop starts, routes events
//! to it, keeps frames coming (slowly while minimized), and remembers a fatal error.

use super::options::{AppOptions, Startup};
use super::session::{Flow, Session};
use lucid_engine::Context;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::window::WindowId;

/// How often a minimized window checks whether it has a size again.
const MINIMIZED_POLL: Duration = Duration::from_millis(100);

/// The sandbox as a winit application.
pub struct App {
    options: AppOptions,
    startup: Startup,
    session: Option<Session>,
    context: Option<Context>,
    error: Option<anyhow::Error>,
}

impl App {
    /// An app that opens a window with `options`, rendering as `startup` says, when the event
    /// loop starts.
    pub fn new(options: AppOptions, startup: Startup) -> Self {
        Self {
            options,
            startup,
            session: None,
            context: None,
            error: None,
        }
    }

    /// Ends the session; returns the error that stopped the app (if any) and the context, whose
    /// validation log the caller checks once everything else is gone.
    pub fn finish(mut self) -> (anyhow::Result<()>, Option<Context>) {
        self.session = None;
        let result = self.error.map_or(Ok(()), Err);
        (result, self.context)
    }

    fn stop(&mut self, event_loop: &ActiveEventLoop, error: Option<anyhow::Error>) {
        if self.error.is_none() {
            self.error = error;
        }
        self.session = None;
        event_loop.exit();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.session.is_some() || self.error.is_some() {
            return;
        }
        match Session::new(event_loop, &self.options, &self.startup) {
            Ok(session) => {
                self.context = Some(session.context().clone());
                self.session = Some(session);
            }
            Err(e) => self.stop(event_loop, Some(e)),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(session) = &mut self.session else {
            return;
        };
        let flow = if matches!(event, WindowEvent::RedrawRequested) {
            session.redraw()
        } else {
            Ok(session.window_event(&event))
        };
        match flow {
            Ok(Flow::Continue) => {}
            Ok(Flow::Exit) => self.stop(event_loop, None),
            Err(e) => self.stop(event_loop, Some(e)),
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(session) = &self.session else {
            return;
        };
        if session.is_minimized() {
            event_loop.set_control_flow(ControlFlow::WaitUntil(Instant::now() + MINIMIZED_POLL));
        } else {
            event_loop.set_control_flow(ControlFlow::Poll);
        }
        session.window().request_redraw();
    }

    fn exiting(&mut self, _: &ActiveEventLoop) {
        self.session = None;
    }
}
