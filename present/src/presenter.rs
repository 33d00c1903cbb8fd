//! Presenting render-graph frames to a window, for the sandbox and for applications embedding
//! Lucid: the context with a surface, the swapchain, the frames in flight, and what
//! [`SurfaceState`] decides on resizes, minimization, out-of-date swapchains and lost surfaces.

use crate::surface_state::{Prepare, SurfaceState};
use crate::target::{acquire_wait_stage, PresentTarget};
use crate::{create_context, FrameRing, Swapchain};
use anyhow::Context as _;
use lucid_engine::graph::{CompiledGraph, Executor, FrameOutputs, SubmitOptions};
use lucid_engine::Context;
use std::sync::Arc;
use winit::window::Window;

/// What [`Presenter::begin`] found.
///
/// ```no_run
/// # fn frame(presenter: &mut lucid_present::Presenter<Option<lucid_engine::graph::ReadbackId>>, executor: &mut lucid_engine::graph::Executor) -> anyhow::Result<()> {
/// let began = presenter.begin(executor)?;
/// for (outputs, readback) in began.finished {
///     if let Some(id) = readback {
///         let image = outputs.image(id)?; // what that frame read back
///     }
/// }
/// if began.target.is_none() {
///     return Ok(()); // minimized or recreating: nothing to draw this time
/// }
/// # Ok(()) }
/// ```
pub struct Began<T> {
    /// The image to draw on, or `None` when this frame is skipped (minimized window, swapchain
    /// being recreated, no image in time).
    pub target: Option<PresentTarget>,
    /// Frames that completed meanwhile, with the payloads they were submitted with, oldest first.
    pub finished: Vec<(FrameOutputs, T)>,
    /// The swapchain was recreated (its images and size changed).
    pub recreated: bool,
}

/// A window's presentation. `T` is what each frame carries until it completes (e.g. where to save
/// its readbacks).
///
/// ```no_run
/// # fn frame(presenter: &mut lucid_present::Presenter, renderer: &mut lucid_passes::renderer::Renderer) -> anyhow::Result<()> {
/// // Each redraw: take an image, render at its size, draw on it, present.
/// let began = presenter.begin(renderer.executor_mut())?;
/// if let Some(target) = began.target {
///     let [width, height] = target.extent();
///     renderer.resize(width, height)?;
///     let mut graph = lucid_engine::graph::RenderGraph::new();
///     let (images, _) = renderer.add_frame(&mut graph);
///     let encoding = lucid_engine::capture::PngEncoding {
///         exposure: 0.0,
///         tone: lucid_engine::capture::ToneCurve::Aces,
///     };
///     target.add_display(&mut graph, images.hdr, encoding);
///     presenter.submit(renderer.executor_mut(), target, graph.compile()?, ())?;
/// }
/// # Ok(()) }
/// ```
pub struct Presenter<T = ()> {
    state: SurfaceState,
    ring: FrameRing<T>,
    swapchain: Swapchain,
    ctx: Context,
    window: Arc<Window>,
}

impl<T> Presenter<T> {
    /// Creates a Vulkan context (validation and device from the environment) that can present to
    /// `window`, and the window's swapchain.
    ///
    /// ```no_run
    /// # fn open(event_loop: &winit::event_loop::ActiveEventLoop) -> anyhow::Result<()> {
    /// use std::sync::Arc;
    /// let window = Arc::new(event_loop.create_window(Default::default())?);
    /// let presenter: lucid_present::Presenter = lucid_present::Presenter::new(window)?;
    /// let ctx = presenter.context(); // create the renderer on it
    /// # Ok(()) }
    /// ```
    pub fn new(window: Arc<Window>) -> anyhow::Result<Self> {
        let (ctx, surface) = create_context(&window)?;
        let size = window.inner_size();
        let size = [size.width, size.height];
        let swapchain = Swapchain::new(&ctx, surface, size)?;
        Ok(Self {
            state: SurfaceState::new(size),
            ring: FrameRing::new(&ctx)?,
            swapchain,
            ctx,
            window,
        })
    }

    /// The context (create the renderer on it).
    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// The window.
    pub fn window(&self) -> &Arc<Window> {
        &self.window
    }

    /// Tells the presenter the window's new size, from `WindowEvent::Resized` (zero when
    /// minimized) or after `WindowEvent::ScaleFactorChanged`.
    ///
    /// ```no_run
    /// # fn on_event(presenter: &mut lucid_present::Presenter, event: winit::event::WindowEvent) {
    /// use winit::event::WindowEvent;
    /// match event {
    ///     WindowEvent::Resized(size) => presenter.resized([size.width, size.height]),
    ///     WindowEvent::ScaleFactorChanged { .. } => {
    ///         let size = presenter.window().inner_size();
    ///         presenter.resized([size.width, size.height]);
    ///     }
    ///     _ => {}
    /// }
    /// # }
    /// ```
    pub fn resized(&mut self, size: [u32; 2]) {
        self.state.resized(size);
    }

    /// The window's size as last told by [`Self::resized`] (at first, its size when the presenter
    /// was made).
    pub fn size(&self) -> [u32; 2] {
        self.state.size()
    }

    /// Whether there is nothing to draw on (a zero-size window, or a surface without a size); an
    /// event loop can poll slowly meanwhile.
    ///
    /// ```no_run
    /// # fn about_to_wait(presenter: &lucid_present::Presenter, event_loop: &winit::event_loop::ActiveEventLoop) {
    /// use std::time::{Duration, Instant};
    /// use winit::event_loop::ControlFlow;
    /// event_loop.set_control_flow(if presenter.is_minimized() {
    ///     ControlFlow::WaitUntil(Instant::now() + Duration::from_millis(100))
    /// } else {
    ///     ControlFlow::Poll
    /// });
    /// presenter.window().request_redraw();
    /// # }
    /// ```
    pub fn is_minimized(&self) -> bool {
        self.state.is_minimized() || !self.swapchain.is_usable()
    }

    /// Starts a frame: recreates the swapchain (and surface) when needed, waits for the frame slot
    /// that is reused next, and acquires an image. `executor` runs the frames.
    pub fn begin(&mut self, executor: &mut Executor) -> anyhow::Result<Began<T>> {
        let mut began = Began {
            target: None,
            finished: Vec::new(),
            recreated: false,
        };
        match self.state.prepare(self.swapchain.is_usable()) {
            Prepare::Skip => return Ok(began),
            Prepare::Recreate { surface } => {
                began.finished = self.ring.drain(executor)?;
                self.ctx.wait_idle()?;
                if surface {
                    self.swapchain.replace_surface(&self.window)?;
                }
                self.swapchain
                    .recreate(self.state.size())
                    .context("recreating the swapchain")?;
                self.state.recreated();
                began.recreated = true;
                if !self.swapchain.is_usable() {
                    return Ok(began);
                }
            }
            Prepare::Draw => {}
        }
        began.finished.extend(self.ring.wait_next(executor)?);
        let acquired = self.swapchain.acquire(self.ring.acquire_semaphore());
        began.target = self.state.acquired(acquired)?.map(|index| {
            PresentTarget::new(index, self.swapchain.images()[index as usize].clone())
        });
        Ok(began)
    }

    /// Submits `graph`, which draws on `target` and leaves it ready to present (e.g. through
    /// [`PresentTarget::add_display`]), on `executor` and presents it. `payload` comes back with
    /// the frame's outputs from a later [`Self::begin`] or [`Self::finish`].
    pub fn submit(
        &mut self,
        executor: &mut Executor,
        target: PresentTarget,
        graph: CompiledGraph,
        payload: T,
    ) -> anyhow::Result<()> {
        let submit = SubmitOptions {
            wait: vec![(self.ring.acquire_semaphore(), acquire_wait_stage())],
            signal: vec![self.swapchain.render_finished(target.index())],
        };
        let frame = match executor.execute_with(graph, &submit) {
            Ok(frame) => frame,
            Err(e) => {
                self.abandon(target)?;
                return Err(e.into());
            }
        };
        self.ring.submitted(frame, payload);
        let presented = self.swapchain.present(target.index());
        self.state.presented(presented)
    }

    /// Gives up a frame whose image was acquired but that could not be submitted (the target is
    /// used up); the swapchain is recreated before the next frame.
    ///
    /// ```no_run
    /// # fn frame(presenter: &mut lucid_present::Presenter, target: lucid_present::PresentTarget, build: impl FnOnce() -> anyhow::Result<lucid_engine::graph::RenderGraph>, executor: &mut lucid_engine::graph::Executor) -> anyhow::Result<()> {
    /// match build().and_then(|graph| Ok(graph.compile()?)) {
    ///     Ok(compiled) => presenter.submit(executor, target, compiled, ())?,
    ///     Err(e) => {
    ///         presenter.abandon(target)?;
    ///         eprintln!("frame skipped: {e:#}");
    ///     }
    /// }
    /// # Ok(()) }
    /// ```
    pub fn abandon(&mut self, _target: PresentTarget) -> anyhow::Result<()> {
        self.ring.consume_acquire()?;
        self.ctx.wait_idle()?;
        self.state.frame_failed();
        Ok(())
    }

    /// Waits for every frame in flight; returns their outputs and payloads, oldest first.
    ///
    /// ```no_run
    /// # fn shut_down(mut presenter: lucid_present::Presenter, mut renderer: lucid_passes::renderer::Renderer) -> anyhow::Result<()> {
    /// presenter.finish(renderer.executor_mut())?; // before the renderer goes
    /// drop(renderer);
    /// # Ok(()) }
    /// ```
    pub fn finish(&mut self, executor: &mut Executor) -> anyhow::Result<Vec<(FrameOutputs, T)>> {
        self.ring.drain(executor)
    }

    /// The swapchain (e.g. to make a framebuffer per image for a UI drawn over the frame; remake
    /// them when [`Began::recreated`] says so).
    pub fn swapchain(&self) -> &Swapchain {
        &self.swapchain
    }

    /// Reports the surface lost, as the window system would (for self-tests of the recovery: the
    /// next [`Self::begin`] makes a new surface and swapchain); fails after too many in a row.
    pub fn report_surface_lost(&mut self) -> anyhow::Result<()> {
        self.state.lost()
    }
}
