//! The game in a window: winit's event loop, the simulation in fixed steps, one rendered frame per
//! redraw, presented through `lucid_present::Presenter`, and the frame rate in the title.

use crate::game::{FixedStep, Game, TICKS_PER_SECOND};
use crate::Options;
use anyhow::Context as _;
use lucid_engine::capture::{PngEncoding, ToneCurve};
use lucid_engine::graph::RenderGraph;
use lucid_engine::scene::builtin;
use lucid_passes::renderer::Renderer;
use lucid_present::Presenter;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

/// The display transform: exposure unchanged, the ACES filmic curve.
const DISPLAY: PngEncoding = PngEncoding {
    exposure: 0.0,
    tone: ToneCurve::Aces,
};
/// How often the title's frame rate is updated.
const TITLE_INTERVAL: Duration = Duration::from_millis(500);
/// How often a minimized window checks whether it has a size again.
const MINIMIZED_POLL: Duration = Duration::from_millis(100);

/// Opens the window and runs until it is closed or `options.frames` frames were presented;
/// returns a summary line. Without a display it fails with a one-line hint to use `--headless`.
pub fn run(options: &Options) -> anyhow::Result<String> {
    run_with(options, false)
}

/// [`run`]; `any_thread` lets the event loop run off the main thread (the tests do).
pub fn run_with(options: &Options, any_thread: bool) -> anyhow::Result<String> {
    if !lucid_present::display_available() {
        anyhow::bail!(
            "no display to open a window on; run with --headless (e.g. --headless --frames 60)"
        );
    }
    let mut builder = EventLoop::builder();
    #[cfg(all(unix, not(target_os = "macos"), not(target_os = "android")))]
    {
        use winit::platform::{wayland::EventLoopBuilderExtWayland, x11::EventLoopBuilderExtX11};
        EventLoopBuilderExtX11::with_any_thread(&mut builder, any_thread);
        EventLoopBuilderExtWayland::with_any_thread(&mut builder, any_thread);
    }
    #[cfg(not(all(unix, not(target_os = "macos"), not(target_os = "android"))))]
    let _ = any_thread;
    let event_loop = builder
        .build()
        .map_err(|e| anyhow::anyhow!("cannot open the display ({e}); run with --headless"))?;
    let mut app = App {
        options,
        running: None,
        result: Ok(String::new()),
    };
    event_loop
        .run_app(&mut app)
        .context("the window event loop failed")?;
    app.result
}

/// The game while its window is open.
struct Running {
    renderer: Renderer,
    // Dropped after the renderer, whose frames it presented.
    presenter: Presenter,
    game: Game,
    step: FixedStep,
    tick: u64,
    started: Instant,
    last_frame: Instant,
    presented: u32,
    title_frames: u32,
    title_since: Instant,
}

struct App<'a> {
    options: &'a Options,
    running: Option<Running>,
    result: anyhow::Result<String>,
}

impl App<'_> {
    fn start(&self, event_loop: &ActiveEventLoop) -> anyhow::Result<Running> {
        let (width, height) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title("Lucid game loop")
            .with_inner_size(PhysicalSize::new(width, height));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("opening the window")?,
        );
        let presenter = Presenter::new(window)?;
        let scene = builtin::build("cornell-box")?;
        let size = presenter.window().inner_size();
        let renderer = Renderer::new(
            presenter.context(),
            scene,
            size.width.max(1),
            size.height.max(1),
            self.options.settings(),
        )?;
        let game = Game::new(&renderer, self.options.camera_moves);
        let now = Instant::now();
        Ok(Running {
            renderer,
            presenter,
            game,
            step: FixedStep::default(),
            tick: 0,
            started: now,
            last_frame: now,
            presented: 0,
            title_frames: 0,
            title_since: now,
        })
    }

    /// Ends the game with `result`; on success, the summary, unless validation (when on)
    /// reported anything.
    fn stop(&mut self, event_loop: &ActiveEventLoop, result: anyhow::Result<()>) {
        event_loop.exit();
        let Some(running) = self.running.take() else {
            self.result = result.map(|()| "the window closed before the game started".into());
            return;
        };
        let ctx = running.presenter.context().clone();
        let summary = running.summary();
        drop(running);
        let report = ctx.validation_log().take_report();
        self.result = result.and_then(|()| match report {
            Some(report) => Err(anyhow::anyhow!(report)),
            None => Ok(summary),
        });
    }
}

impl Running {
    /// Simulates the time since the last frame in fixed steps, renders and presents a frame;
    /// returns whether the game is over (`frames` presented).
    fn frame(&mut self, frames: Option<u32>) -> anyhow::Result<bool> {
        let now = Instant::now();
        let elapsed = now.duration_since(self.last_frame).as_secs_f64();
        self.last_frame = now;
        // The world is a function of the tick, so simulating the steps is counting them.
        self.tick += u64::from(self.step.advance(elapsed));
        self.game.apply(&mut self.renderer, self.tick)?;

        let began = self.presenter.begin(self.renderer.executor_mut())?;
        let Some(target) = began.target else {
            return Ok(false);
        };
        let [width, height] = target.extent();
        self.renderer.resize(width, height)?;
        let mut graph = RenderGraph::new();
        let (images, _) = self.renderer.add_frame(&mut graph);
        target.add_display(&mut graph, images.hdr, DISPLAY);
        let compiled = graph.compile()?;
        self.presenter
            .submit(self.renderer.executor_mut(), target, compiled, ())?;
        self.presented += 1;
        self.update_title(now);
        Ok(frames.is_some_and(|n| self.presented >= n))
    }

    fn update_title(&mut self, now: Instant) {
        self.title_frames += 1;
        let since = now.duration_since(self.title_since);
        if since >= TITLE_INTERVAL {
            let fps = f64::from(self.title_frames) / since.as_secs_f64();
            self.presenter.window().set_title(&format!(
                "Lucid game loop: {fps:.1} fps, tick {} ({TICKS_PER_SECOND} Hz)",
                self.tick
            ));
            self.title_frames = 0;
            self.title_since = now;
        }
    }

    fn summary(&self) -> String {
        let seconds = self.started.elapsed().as_secs_f64();
        format!(
            "presented {} frames in {seconds:.2} s ({:.1} fps), {} ticks of 1/{TICKS_PER_SECOND} s",
            self.presented,
            f64::from(self.presented) / seconds.max(1e-9),
            self.tick
        )
    }
}

impl ApplicationHandler for App<'_> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match self.start(event_loop) {
            Ok(running) => self.running = Some(running),
            Err(e) => self.stop(event_loop, Err(e)),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(running) = &mut self.running else {
            return;
        };
        let outcome = match event {
            WindowEvent::CloseRequested => Ok(true),
            WindowEvent::Resized(size) => {
                running.presenter.resized([size.width, size.height]);
                Ok(false)
            }
            WindowEvent::ScaleFactorChanged { .. } => {
                let size = running.presenter.window().inner_size();
                running.presenter.resized([size.width, size.height]);
                Ok(false)
            }
            WindowEvent::RedrawRequested => running.frame(self.options.frames),
            _ => Ok(false),
        };
        match outcome {
            Ok(false) => {}
            Ok(true) => self.stop(event_loop, Ok(())),
            Err(e) => self.stop(event_loop, Err(e)),
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(running) = &self.running else {
            return;
        };
        if running.presenter.is_minimized() {
            event_loop.set_control_flow(ControlFlow::WaitUntil(Instant::now() + MINIMIZED_POLL));
        } else {
            event_loop.set_control_flow(ControlFlow::Poll);
        }
        running.presenter.window().request_redraw();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xvfb;
    use std::process::Command;

    /// Set in the process that runs the game.
    const CHILD: &str = "LUCID_GAME_LOOP_WINDOW";
    const FRAMES: u32 = 8;
    const CHILD_TEST: &str = "windowed::tests::windowed_game";

    /// Runs [`windowed_game`] in a process of its own (winit wants one event loop per process) on
    /// an Xvfb display, and checks that it presented the frames asked for and exited cleanly.
    #[test]
    fn the_windowed_game_presents_frames_at_a_fixed_step_and_exits() {
        let xvfb = xvfb::Xvfb::start().unwrap_or_else(|e| panic!("{e}"));
        let mut command = Command::new(std::env::current_exe().unwrap());
        command
            .args(["--exact", CHILD_TEST, "--ignored", "--nocapture"])
            .env(CHILD, "1");
        let output = xvfb.run(command).unwrap_or_else(|e| panic!("{e}"));
        xvfb::check_clean_exit(&output).unwrap_or_else(|e| panic!("{e}"));
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(stdout.contains("1 passed"), "the game ran:\n{stdout}");
        let summary = stdout
            .lines()
            .find(|l| l.starts_with("presented "))
            .unwrap_or_else(|| panic!("no summary in:\n{stdout}"));
        println!("{summary}");
        let words: Vec<&str> = summary.split_whitespace().collect();
        let presented: u32 = words[1].parse().unwrap();
        let seconds: f64 = words[4].parse().unwrap();
        let ticks: f64 = words[8].parse().unwrap();
        assert_eq!(presented, FRAMES, "{summary}");
        assert!(ticks >= 1.0, "the simulation advanced: {summary}");
        assert!(
            ticks <= seconds * TICKS_PER_SECOND + 1.0,
            "at most one tick per 1/60 s of wall time: {summary}"
        );
    }

    /// The windowed game itself (run by the test above; does nothing when run otherwise).
    #[test]
    #[ignore = "run under Xvfb by the_windowed_game_presents_frames_at_a_fixed_step_and_exits"]
    fn windowed_game() {
        if std::env::var_os(CHILD).is_none() {
            return;
        }
        let options = Options {
            headless: false,
            frames: Some(FRAMES),
            every: 1,
            size: (160, 96),
            spp: lucid_passes::renderer::SamplesPerPixel::ONE,
            svgf: true,
            camera_moves: true,
            out: std::env::temp_dir(),
        };
        println!("{}", run_with(&options, true).unwrap());
    }
}
