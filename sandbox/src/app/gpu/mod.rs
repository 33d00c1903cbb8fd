//! Vulkan for the window: the context with a surface, the swapchain, and the ring of frames in
//! flight with their acquire semaphores.

mod frames;
mod surface;
mod swapchain;

pub use frames::FrameRing;
pub use surface::{create_context, WindowSurface};
pub use swapchain::{Acquired, Swapchain};

use ash::vk;

/// Turns a Vulkan result code into an engine error naming the call.
pub fn vk_error(call: &'static str) -> impl FnOnce(vk::Result) -> lucid_engine::EngineError {
    move |result| lucid_engine::EngineError::Vulkan { call, result }
}
