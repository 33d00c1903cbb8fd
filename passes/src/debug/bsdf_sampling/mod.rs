//! The BSDFs' sampling against their evaluation, over a buffer of cases
//! (`shaders/bsdf_sampling/bsdf_sampling.comp`): each case's sample (direction, weight, pdf and the
//! reverse pdf bidirectional MIS reads) beside what evaluating the BSDF for the sample's two
//! directions gives, so that a test can check that the two agree.

use crate::shaders::bsdf_sampling::BSDF_SAMPLING;
use lucid_engine::graph::{BufferHandle, RenderGraph};

/// One case: a BSDF, an outgoing direction and the sample's random numbers (`BsdfCase` in the
/// shader, std430).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BsdfCase {
    /// Base colour (rgb) and GGX alpha.
    pub color_alpha: [f32; 4],
    /// The outgoing direction in the shading frame (unit; +z is the normal) and the index of
    /// refraction.
    pub wo_ior: [f32; 4],
    /// The sample's three random numbers and the metallic share.
    pub u_metallic: [f32; 4],
    /// The material kind (`MATERIAL_*` in `shaders/common/material_kinds.glsl`), 1 for a delta
    /// lobe, two zeros.
    pub kind_smooth: [u32; 4],
}

/// What sampling and evaluating a case gave (`BsdfOutcome` in the shader, std430).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BsdfOutcome {
    /// The sampled direction, and 1 where sampling succeeded (else 0).
    pub wi_sampled: [f32; 4],
    /// The sample's weight (f cos / pdf) and pdf.
    pub weight_pdf: [f32; 4],
    /// The sample's reverse pdf, 1 for a delta lobe, and the evaluation's pdf and reverse pdf
    /// (zero for delta lobes and failed samples).
    pub rev_delta: [f32; 4],
    /// The evaluation's value for wo -> wi, cosine included (rgb), and 0.
    pub value: [f32; 4],
}

/// Adds a pass sampling and evaluating `count` [`BsdfCase`]s of `cases`; returns the buffer of
/// their [`BsdfOutcome`]s.
pub fn add_bsdf_sampling(g: &mut RenderGraph, cases: BufferHandle, count: u32) -> BufferHandle {
    let mut pass = g.compute_pass("bsdf_sampling", &BSDF_SAMPLING);
    pass.read("b_cases", cases);
    let bytes = std::mem::size_of::<BsdfOutcome>() as u64 * u64::from(count.max(1));
    let outcomes = pass.create_buffer("b_outcomes", "bsdf_sampling.outcomes", bytes);
    pass.push(&count);
    pass.dispatch([count, 1, 1]);
    outcomes
}
