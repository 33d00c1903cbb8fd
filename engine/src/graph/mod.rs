//! The frame render graph, after Frostbite's frame graph with kajiya's typed handles.
//!
//! **Setup**: passes declare the resources they create, read and write ([`RenderGraph::add_pass`]).
//! **Compile** ([`RenderGraph::compile`]): plain data, no Vulkan: cull, order, barriers, transient
//! lifetimes and aliasing ([`Plan`]). **Execute** ([`Executor::execute`]): record, submit, time.
//!
//! ```no_run
//! # use lucid_engine::graph::*; use lucid_engine::memory::ImageDesc;
//! # fn demo(executor: &mut Executor, shader: &'static lucid_engine::shader::ShaderSource) -> lucid_engine::Result<()> {
//! let mut g = RenderGraph::new();
//! let mut p = g.add_pass("fill");
//! let out = p.create_image("out", ImageDesc::rgba32f(64, 64));
//! let out = p.write(out, Access::ComputeWrite);
//! p.execute(move |ctx| ctx.compute(shader).image("u_out", out).dispatch_threads([64, 64, 1]));
//! let readback = g.readback(out);
//! let frame = executor.execute(g.compile()?)?;
//! let outputs = executor.wait(frame)?;
//! let image = outputs.image(readback)?;
//! # Ok(()) }
//! ```

mod compile;
mod compute_pass;
mod dump;
mod executor;
mod frame_slot;
mod handle;
mod pass_context;
mod plan;
mod render_graph;
mod temporal;
mod transients;

pub use crate::access::{Access, AccessInfo};
pub use crate::error::GraphError;
pub use compute_pass::ComputePass;
pub use executor::{Executor, FrameId, FrameOutputs, PassTiming, SubmitOptions};
pub use handle::{BufferHandle, Handle, ImageHandle, ResourceId, TemporalImage};
pub use pass_context::{Dispatch, PassContext};
pub use plan::{AliasSlot, Barrier, BarrierSrc, Plan, PlannedPass, PlannedResource};
pub use render_graph::{
    PassBuilder, PassFn, ReadbackId, RenderGraph, ResourceDecl, ResourceDesc, ResourceKind,
};
pub use temporal::{TemporalSlots, TemporalStore};

/// A compiled graph: the plan and the work of its kept passes, ready to execute.
pub struct CompiledGraph {
    /// Order, barriers, lifetimes and aliasing as plain data.
    pub plan: Plan,
    pub(crate) work: Vec<render_graph::PassWork>,
    pub(crate) externals: Vec<(ResourceId, render_graph::External)>,
    pub(crate) readbacks: Vec<(usize, ResourceId)>,
}
