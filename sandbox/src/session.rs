//! A running sandbox window: the window, its GPU objects, the frame source and the app state,
//! and how window events change them.

use super::camera::Pose;
use super::frame_source::{FrameSource, RendererSource, TestPatternSource};
use super::input::{Action, Input};
use super::options::{AppOptions, Startup};
use super::overlay::Overlay;
use super::pending::Pending;
use super::state::{AppState, PathMode};
use super::stats::FrameStats;
use super::window_test::WindowTest;
use super::{scene, ui};
use anyhow::Context as _;
use glam::Vec2;
use lucid_engine::Context;
use lucid_present::Presenter;
use std::sync::Arc;
use std::time::Instant;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseScrollDelta, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::PhysicalKey;
use winit::window::Window;

/// Pixels of a touchpad scroll that count as one wheel step.
const PIXELS_PER_WHEEL_STEP: f32 = 50.0;

/// Whether the app goes on after an event or frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Keep running.
    Continue,
    /// Close the window and exit.
    Exit,
}

/// Everything that lives as long as the window. Fields drop in order: GPU users (the UI's
/// framebuffers use the swapchain's images) before the presenter, which drops the swapchain (and
/// surface) before its window.
pub struct Session {
    pub(super) state: AppState,
    pub(super) input: Input,
    pub(super) stats: FrameStats,
    pub(super) source: Box<dyn FrameSource>,
    pub(super) overlay: Overlay,
    pub(super) presenter: Presenter<Pending>,
    pub(super) ctx: Context,
    pub(super) window: Arc<Window>,
    pub(super) options: AppOptions,
    pub(super) clock: Instant,
    pub(super) last_frame: f64,
    pub(super) frames_presented: u64,
    pub(super) failures_in_a_row: u32,
    /// Recompiles shaders edited under `shaders/` while the app runs.
    pub(super) shader_watcher: lucid_passes::plumbing::hot_reload::ShaderWatcher,
    pub(super) last_shader_check: f64,
    pub(super) capture_requested: bool,
    pub(super) exit: bool,
    /// The window self-test, when asked for.
    pub(super) window_test: Option<WindowTest>,
}

impl Session {
    /// Opens the window and sets up Vulkan, the UI and the scene, rendering as `startup` says.
    pub fn new(
        event_loop: &ActiveEventLoop,
        options: &AppOptions,
        startup: &Startup,
    ) -> anyhow::Result<Self> {
        let attributes = Window::default_attributes()
            .with_title(format!("Lucid — {}", options.scene))
            .with_inner_size(PhysicalSize::new(options.size[0], options.size[1]));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("opening the window")?,
        );
        let presenter = Presenter::new(window.clone())?;
        let ctx = presenter.context().clone();
        let swapchain = presenter.swapchain();
        let mut overlay = Overlay::new(&ctx, &window, swapchain.format())?;
        overlay.set_targets(swapchain.format(), swapchain.views(), swapchain.extent())?;
        let mut state = AppState::new(
            &options.scene,
            scene::load(&options.scene, options.env.as_deref()),
        );
        state.render = startup.render;
        state.split = startup.split;
        let extent = swapchain.extent();
        let source = frame_source_for(&ctx, &state, [extent.width, extent.height])?;
        let mut session = Self {
            state,
            input: Input::default(),
            stats: FrameStats::default(),
            source,
            overlay,
            presenter,
            ctx,
            window,
            options: options.clone(),
            clock: Instant::now(),
            last_frame: 0.0,
            frames_presented: 0,
            failures_in_a_row: 0,
            shader_watcher: lucid_passes::plumbing::hot_reload::ShaderWatcher::new(
                lucid_passes::plumbing::hot_reload::source_shader_dir(),
            ),
            last_shader_check: 0.0,
            capture_requested: false,
            exit: false,
            window_test: startup.window_test.then(|| WindowTest::new(options.size)),
        };
        if startup.calibrate {
            session.calibrate();
        }
        Ok(session)
    }

    /// The context (for the validation check after the session ends).
    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// The window.
    pub fn window(&self) -> &Window {
        &self.window
    }

    /// Whether there is nothing to draw on (zero-size window).
    pub fn is_minimized(&self) -> bool {
        self.presenter.is_minimized()
    }

    /// Handles one window event (except redraws).
    pub fn window_event(&mut self, event: &WindowEvent) -> Flow {
        let consumed = self.overlay.on_window_event(&self.window, event);
        match event {
            WindowEvent::CloseRequested | WindowEvent::Destroyed => return Flow::Exit,
            WindowEvent::Resized(size) => self.presenter.resized([size.width, size.height]),
            WindowEvent::ScaleFactorChanged { .. } => {
                let size = self.window.inner_size();
                self.presenter.resized([size.width, size.height]);
            }
            WindowEvent::Focused(false) => self.input.release_all(),
            WindowEvent::ModifiersChanged(m) => self.input.set_shift(m.state().shift_key()),
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(code) = event.physical_key else {
                    return Flow::Continue;
                };
                let pressed = event.state == ElementState::Pressed;
                if !pressed || !(consumed || self.overlay.wants_keyboard()) {
                    if let Some(action) = self.input.key(code, pressed, event.repeat) {
                        self.act(action);
                    }
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let pressed = *state == ElementState::Pressed;
                if !pressed || !self.overlay.wants_pointer() {
                    self.input.mouse_button(*button, pressed);
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                self.input
                    .cursor(Vec2::new(position.x as f32, position.y as f32));
            }
            WindowEvent::MouseWheel { delta, .. } if !self.overlay.wants_pointer() => {
                self.input.wheel(match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / PIXELS_PER_WHEEL_STEP,
                });
            }
            _ => {}
        }
        Flow::Continue
    }

    fn act(&mut self, action: Action) {
        match action {
            Action::Capture => self.capture_requested = true,
            Action::FrameScene => {
                if let Ok(info) = &self.state.scene {
                    let vfov = self.state.camera.pose.vfov_degrees;
                    self.state.camera.pose = Pose::from_camera(&info.framing(vfov));
                    self.state.path = PathMode::Idle;
                    self.state.message = Some("framed the scene's bounds (F)".into());
                }
            }
            Action::Store(key) => {
                self.state.bookmarks.store(key, self.state.camera.pose);
                self.state.message = Some(format!("stored the camera in bookmark {key}"));
            }
            Action::Recall(key) => match self.state.bookmarks.recall(key) {
                Some(pose) => {
                    self.state.camera.pose = pose;
                    self.state.path = PathMode::Idle;
                }
                None => {
                    self.state.message =
                        Some(format!("bookmark {key} is empty: Shift+{key} stores one"))
                }
            },
        }
    }

    /// Renders the newly loaded scene: waits for the frames of the old source first.
    fn replace_source(&mut self) -> anyhow::Result<()> {
        self.finish_all()?;
        let extent = self.presenter.swapchain().extent();
        self.source = frame_source_for(&self.ctx, &self.state, [extent.width, extent.height])?;
        Ok(())
    }

    /// Acts on the panel's buttons.
    pub(super) fn handle_requests(&mut self, requests: ui::Requests, now: f64) {
        if let Some(spec) = requests.load_scene {
            let loaded = scene::load(&spec, self.options.env.as_deref());
            self.state.set_scene(loaded);
            self.window.set_title(&format!("Lucid — {spec}"));
            if let Err(e) = self.replace_source() {
                self.state.message = Some(format!("{e:#}"));
            }
        }
        self.capture_requested |= requests.capture;
        if requests.calibrate {
            self.calibrate();
        }
        if requests.record {
            self.state.path = PathMode::Recording(Default::default(), now);
            self.state.message = Some("recording the camera path".into());
        }
        if requests.replay {
            match super::camera::PathPlayer::load(self.state.path_file.as_ref()) {
                Ok(player) => self.state.path = PathMode::Replaying(player, now),
                Err(e) => self.state.message = Some(format!("{e:#}")),
            }
        }
        if requests.stop {
            let mode = std::mem::replace(&mut self.state.path, PathMode::Idle);
            if let PathMode::Recording(recorder, _) = mode {
                let file = self.state.path_file.clone();
                self.state.message = Some(match recorder.save(file.as_ref()) {
                    Ok(()) => format!("saved camera path {file}"),
                    Err(e) => format!("{e:#}"),
                });
            }
        }
    }

    /// Runs the calibration on the current view and switches the renderer (the left half in a
    /// split view) to its choice; the panel shows the choice and the reason, or the error.
    fn calibrate(&mut self) {
        let goal = self.state.auto.goal();
        let result = self
            .finish_all()
            .and_then(|()| self.source.calibrate(goal))
            .map(|(calibration, choice)| {
                let render = &mut self.state.render;
                render.algorithm = choice.config.algorithm;
                render.denoiser = choice.config.denoiser;
                render.spp = choice.config.spp;
                crate::auto::Calibrated {
                    choice,
                    goal: goal.describe(),
                    seconds: calibration.seconds,
                }
            });
        self.state.message = Some(match &result {
            Ok(c) => format!("auto: {}", c.choice.config.name()),
            Err(e) => format!("calibration failed: {e:#}"),
        });
        self.state.auto.last = Some(result.map_err(|e| format!("{e:#}")));
    }

    /// Moves the camera by input, or along the replayed path, and records it if recording.
    pub(super) fn update_camera(&mut self, now: f64, dt: f64) {
        let input = self.input.take();
        let replayed = match &self.state.path {
            PathMode::Replaying(player, start) => Some(player.sample((now - start) as f32)),
            _ => None,
        };
        match replayed {
            Some(Some(pose)) => self.state.camera.pose = pose,
            Some(None) => {
                self.state.path = PathMode::Idle;
                self.state.message = Some("camera path replay finished".into());
            }
            None => {
                self.state.camera.update(&input, dt as f32);
            }
        }
        if let PathMode::Recording(recorder, start) = &mut self.state.path {
            recorder.record((now - *start) as f32, &self.state.camera.pose);
        }
    }
}

/// The renderer on the loaded scene, or the test pattern while no scene could be loaded (the
/// panel shows why).
fn frame_source_for(
    ctx: &Context,
    state: &AppState,
    extent: [u32; 2],
) -> anyhow::Result<Box<dyn FrameSource>> {
    Ok(match &state.scene {
        Ok(info) => Box::new(RendererSource::new(ctx, (*info.scene).clone(), extent)?),
        Err(_) => Box::new(TestPatternSource::new(ctx)?),
    })
}
