//! Per-frame constants (camera, previous camera, frame index, seed, samples, depth, size), written
//! into a transient buffer inline in the command buffer: no staging, no per-frame allocations.

use bytemuck::{Pod, Zeroable};
use lucid_engine::graph::{Access, BufferHandle, RenderGraph};
use lucid_engine::scene::gpu::GpuCamera;

/// Mirrors `FrameConstants` in `shaders/common/frame.glsl` (std430, 176 bytes), field by field.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FrameConstants {
    /// This frame's camera.
    pub camera: GpuCamera,
    /// Last frame's camera (for motion vectors).
    pub prev_camera: GpuCamera,
    /// Index of this frame (advances every frame; the random numbers depend on it).
    pub frame_index: u32,
    /// Seed of the per-pixel random numbers.
    pub seed: u32,
    /// Samples per pixel of this frame (at least 1: a [`crate::renderer::SamplesPerPixel`]).
    pub samples_per_pixel: u32,
    /// Longest path, in Mitsuba's convention (1: emitters seen directly, 2: direct lighting, ...).
    pub max_depth: u32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Frames accumulated before this one.
    pub accumulated: u32,
    /// Depth from which Russian roulette may end paths.
    pub rr_depth: u32,
    /// Zero: rounds the size up to std430's 16-byte struct alignment (the cameras' `vec4`s).
    pub padding: [u32; 4],
}

/// Adds the pass that writes `constants`; shaders read the result as `b_frame`.
pub fn add_frame_constants(g: &mut RenderGraph, constants: &FrameConstants) -> BufferHandle {
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::{offset_of, size_of};

    /// The offsets std430 gives the fields of `FrameConstants` in `shaders/common/frame.glsl`.
    #[test]
    fn the_layout_is_that_of_the_shaders() {
        assert_eq!(size_of::<GpuCamera>(), 64);
        assert_eq!(offset_of!(FrameConstants, prev_camera), 64);
        let scalars = [
            offset_of!(FrameConstants, frame_index),
            offset_of!(FrameConstants, seed),
            offset_of!(FrameConstants, samples_per_pixel),
            offset_of!(FrameConstants, max_depth),
            offset_of!(FrameConstants, width),
            offset_of!(FrameConstants, height),
            offset_of!(FrameConstants, accumulated),
            offset_of!(FrameConstants, rr_depth),
        ];
        assert_eq!(scalars, [128, 132, 136, 140, 144, 148, 152, 156]);
        assert_eq!(size_of::<FrameConstants>(), 176);
    }
}
