//! What the passes share that is not a pass of its own: the scene's buffers, the per-frame
//! constants, counters, placeholder images, and shader hot reload.

pub mod frame_constants;
pub mod hot_reload;
pub mod placeholder;
pub mod scene_buffers;
pub mod stats;
