//! Light transport: the passes that trace a frame's radiance, one module per algorithm with its
//! shaders in `shaders/<algorithm>/`, and what every one of them produces ([`Outputs`]), so that
//! accumulation and the denoisers work with any of them.
//!
//! To add an algorithm: a module here whose `add_<algorithm>` adds its pass(es) with
//! [`lucid_engine::graph::RenderGraph::compute_pass`], reads the scene
//! ([`crate::plumbing::scene_buffers::SceneHandles::read`]) and the frame constants (`b_frame`),
//! writes its images with [`Images::create`] and returns [`Outputs`]; its GLSL in a new
//! `shaders/<algorithm>/` folder (embedded as `crate::shaders::<algorithm>`); and a case in
//! [`crate::renderer::Algorithm`].

pub mod bdpt;
mod frame;
mod outputs;
mod parking;
pub mod path_trace;
mod sample_batches;
pub mod wavefront;

pub use frame::Frame;
pub use outputs::{Images, Outputs, Replay, ReplayParams, SurfaceImages};
pub use sample_batches::{sample_batches, SampleBatch, SAMPLES_PER_DISPATCH};
