//! What every light-transport pass (path tracing, bidirectional path tracing, ...) produces for a
//! frame, so that accumulation and the denoisers work with any of them.

use lucid_engine::graph::{Access, BufferHandle, ImageHandle, PassBuilder};
use lucid_engine::memory::ImageDesc;

/// Which pixels replay last frame's paths this frame, as the shaders see it (`ReplayParams` in
/// `shaders/common/replay.glsl`): one pixel per stratum of `stratum` x `stratum` pixels traces, in
/// the current scene, the path that last frame's pixel it came from traced (last frame's camera and
/// random numbers), so that a temporal denoiser can compare the two (A-SVGF's gradients).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ReplayParams {
    /// Side of the strata in pixels; 0: nothing is replayed this frame.
    pub stratum: u32,
    /// Last frame's `stratum` (0 when it replayed nothing): a pixel that replayed last frame did
    /// not use its own random numbers, so it is not replayed again.
    pub prev_stratum: u32,
}

/// What a light-transport pass that can replay paths reads to do so.
#[derive(Clone, Copy, Debug)]
pub struct Replay {
    /// Which pixels replay.
    pub params: ReplayParams,
    /// The G-buffer's motion vectors (`rgba16f`, pixels to last frame's position in xy), which
    /// lead a picked pixel to last frame's pixel.
    pub motion: ImageHandle,
}

/// A light-transport pass's images and counters for one frame.
#[derive(Clone, Copy, Debug)]
pub struct Outputs {
    /// Noisy radiance (RGB, alpha 1), `rgba32f`.
    pub radiance: ImageHandle,
    /// The radiance without the first hit's emission, divided by the first hit's albedo, averaged
    /// over the pixel's samples: what the denoisers filter. `rgba32f`.
    pub demodulated: ImageHandle,
    /// The first hit's demodulation albedo averaged over the pixel's samples (white for the sky and
    /// dielectrics), `rgba32f`.
    pub albedo: ImageHandle,
    /// The radiance the first hit emits towards the camera, averaged over the pixel's samples,
    /// `rgba32f`.
    pub emission: ImageHandle,
    /// `[non-finite samples dropped, rays or samples traced, 0, 0]` as u32.
    pub stats: BufferHandle,
}

/// The per-pixel images of [`Outputs`], created and written by one pass.
#[derive(Clone, Copy, Debug)]
pub struct Images {
    /// See [`Outputs::radiance`].
    pub radiance: ImageHandle,
    /// See [`Outputs::demodulated`].
    pub demodulated: ImageHandle,
    /// See [`Outputs::albedo`].
    pub albedo: ImageHandle,
    /// See [`Outputs::emission`].
    pub emission: ImageHandle,
}

impl Images {
    /// Creates the images in pass `p`, named `<prefix>.radiance` and so on, and declares them
    /// written by the pass's compute shader.
    pub fn create(p: &mut PassBuilder<'_>, prefix: &str, width: u32, height: u32) -> Self {
        let mut image = |name: &str, desc: ImageDesc| {
            let handle = p.create_image(&format!("{prefix}.{name}"), desc);
            p.write(handle, Access::ComputeWrite)
        };
        Self {
            radiance: image("radiance", ImageDesc::rgba32f(width, height)),
            demodulated: image("demodulated", ImageDesc::rgba32f(width, height)),
            albedo: image("albedo", ImageDesc::rgba32f(width, height)),
            emission: image("emission", ImageDesc::rgba32f(width, height)),
        }
    }

    /// The [`Outputs`] of these images with the pass's counters.
    pub fn with_stats(self, stats: BufferHandle) -> Outputs {
        Outputs {
            radiance: self.radiance,
            demodulated: self.demodulated,
            albedo: self.albedo,
            emission: self.emission,
            stats,
        }
    }
}
