//! `lucid_present`: Lucid's frames in a winit window, for the sandbox and for applications
//! embedding Lucid. [`Presenter`] owns the context with a surface, the swapchain and the frames in
//! flight, and handles resizes, minimized (zero-size) windows, out-of-date swapchains and lost
//! surfaces; [`PresentTarget`] adds the display passes (tone mapping into the window image) to a
//! frame's render graph. It depends on the engine and the passes only, not on the sandbox app.
//!
//! ```no_run
//! # fn frame(presenter: &mut lucid_present::Presenter, renderer: &mut lucid_passes::renderer::Renderer) -> anyhow::Result<()> {
//! let began = presenter.begin(renderer.executor_mut())?; // no target while minimized
//! if let Some(target) = began.target {
//!     let [width, height] = target.extent();
//!     renderer.resize(width, height)?;
//!     let mut graph = lucid_engine::graph::RenderGraph::new();
//!     let (images, _) = renderer.add_frame(&mut graph);
//!     let encoding = lucid_engine::capture::PngEncoding {
//!         exposure: 0.0,
//!         tone: lucid_engine::capture::ToneCurve::Aces,
//!     };
//!     target.add_display(&mut graph, images.hdr, encoding);
//!     presenter.submit(renderer.executor_mut(), target, graph.compile()?, ())?;
//! }
//! # Ok(()) }
//! ```

mod display;
mod frames;
pub mod image_copy;
mod presenter;
mod surface;
mod surface_state;
mod swapchain;
mod target;

pub use display::available as display_available;
pub use presenter::{Began, Presenter};
pub use swapchain::Swapchain;
pub use target::PresentTarget;

use ash::vk;
use frames::FrameRing;
use surface::{create_context, WindowSurface};

/// Turns a Vulkan result code into an engine error naming the call (a device loss or memory
/// exhaustion into their own variants).
fn vk_error(call: &'static str) -> impl FnOnce(vk::Result) -> lucid_engine::EngineError {
    move |result| lucid_engine::error::from_vk(call, result)
}
