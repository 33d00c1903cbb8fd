//! Vulkan for the window: the context with a surface, the swapchain, the ring of frames in flight
//! with their acquire semaphores, and the presenter that decides (through `SurfaceState`, plain
//! data) what they need.

mod frames;
pub mod image_copy;
mod presenter;
mod surface;
mod surface_state;
mod swapchain;

pub use frames::FrameRing;
pub use presenter::{Began, PresentTarget, Presenter};
pub use surface::{create_context, WindowSurface};
pub use swapchain::Swapchain;

use ash::vk;

/// Turns a Vulkan result code into an engine error naming the call.
pub fn vk_error(call: &'static str) -> impl FnOnce(vk::Result) -> lucid_engine::EngineError {
    move |result| lucid_engine::EngineError::Vulkan { call, result }
}
