//! Lucid's engine: the Vulkan context, GPU memory, shaders with reflection, the frame render graph,
//! scenes and BVHs, frame capture and image metrics.
//!
//! Everything runs headless by default; a window is optional (see [`context::Context::with_surface`]).

mod access;
pub mod atomic_write;
pub mod bvh;
pub mod capture;
pub mod context;
pub mod error;
pub mod graph;
pub mod memory;
pub mod metrics;
pub mod scene;
pub mod shader;

pub use context::{Context, ContextDesc, Validation};
pub use error::{EngineError, Result};
