//! Per-frame constants (camera, previous camera, frame index, seed, samples, depth, size), written
//! into a transient buffer inline in the command buffer: no staging, no per-frame allocations.

use bytemuck::{Pod, Zeroable};
use lucid_engine::graph::{Access, BufferHandle, RenderGraph};
use lucid_engine::scene::gpu::GpuCamera;

/// Mirrors `FrameConstants` in `shaders/common/frame.glsl` (std430, 176 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FrameConstants {
    /// This frame's camera.
    pub camera: GpuCamera,
    /// Last frame's camera (for motion vectors).
    pub prev_camera: GpuCamera,
    /// Frame index, seed, samples per pixel, maximum path depth.
    pub frame: [u32; 4],
    /// Width, height, frames accumulated before this one, flags.
    pub size: [u32; 4],
    /// Russian-roulette start depth, unused ×3.
    pub params: [f32; 4],
}

/// Adds the pass that writes `constants`; shaders read the result as `b_frame`.
pub fn add(g: &mut RenderGraph, constants: &FrameConstants) -> BufferHandle {
    let data = *constants;
    let mut p = g.add_pass("frame_constants");
    let buffer = p.create_buffer(
        "frame_constants",
        std::mem::size_of::<FrameConstants>() as u64,
    );
    let buffer = p.write(buffer, Access::TransferWrite);
    p.execute(move |ctx| ctx.update_buffer(buffer, bytemuck::bytes_of(&data)));
    buffer
}
