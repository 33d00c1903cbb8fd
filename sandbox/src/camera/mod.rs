//! The interactive camera: a fly controller, bookmarks and path recording.

mod bookmarks;
mod fly;
mod recorder;

pub use bookmarks::Bookmarks;
pub use fly::{FlyCamera, FlyInput, Pose};
pub use recorder::{PathPlayer, PathRecorder};
