//! Shaders: embedded SPIR-V, reflection, specialization constants and compute pipelines.
//!
//! GLSL under `shaders/` is compiled to SPIR-V by the `lucid-passes` build script and embedded as
//! [`ShaderSource`] statics. Pipelines are created on first use, keyed by shader and specialization,
//! and bound by reflected names: see [`crate::graph::PassContext::compute`].

mod library;
mod reflect;
mod specialization;
mod statistics;

pub use library::{ComputePipeline, ShaderLibrary};
pub use reflect::{
    reflect, spirv_words, BindingInfo, DescriptorKind, Reflection, SpecConstantInfo, SpecType,
};
pub use specialization::{SpecValue, Specialization};
pub use statistics::{PipelineStatistic, PipelineStatistics, StatisticValue};

/// A compiled shader embedded in the binary.
#[derive(Clone, Copy, Debug)]
pub struct ShaderSource {
    /// A unique name, `<folder>/<file stem>` under `shaders/` (e.g. `svgf/atrous`).
    pub name: &'static str,
    /// The GLSL file it was compiled from, relative to the workspace root (for hot reload).
    pub path: &'static str,
    /// SPIR-V bytes.
    pub spirv: &'static [u8],
}
