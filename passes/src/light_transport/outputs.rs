//! What every light-transport pass (path tracing, bidirectional path tracing, ...) produces for a
//! frame, so that accumulation and the denoisers work with any of them.

use lucid_engine::graph::{BufferHandle, ComputePass, ImageHandle};
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

/// What a denoiser reads of the light transport besides the radiance: per-pixel averages over the
/// pixel's samples, all `rgba32f`. Written only when asked for ([`Images::create`]): the shaders'
/// `SURFACE_OUTPUTS` specialization constant (`shaders/common/transport_outputs.glsl`) drops the
/// stores, and the registers that carry them through the path, when no denoiser runs.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceImages {
    /// The radiance without the first hit's emission, divided by the first hit's albedo: what the
    /// denoisers filter.
    pub demodulated: ImageHandle,
    /// The first hit's demodulation albedo (white for the sky and dielectrics).
    pub albedo: ImageHandle,
    /// The radiance the first hit emits towards the camera.
    pub emission: ImageHandle,
}

/// A light-transport pass's images and counters for one frame.
#[derive(Clone, Copy, Debug)]
pub struct Outputs {
    /// Noisy radiance (RGB, alpha 1), `rgba32f`.
    pub radiance: ImageHandle,
    /// The denoiser's images, when they were asked for.
    pub surface: Option<SurfaceImages>,
    /// `[non-finite samples dropped, rays traced, pixels whose loops the device cut short, 0]` as
    /// u32 ([`crate::light_transport::sample_batches`]).
    pub stats: BufferHandle,
}

/// The per-pixel images of [`Outputs`], created by one pass and bound to its shader by name
/// (`u_radiance`, `u_demodulated`, `u_albedo`, `u_emission`), with `SURFACE_OUTPUTS`.
#[derive(Clone, Copy, Debug)]
pub struct Images {
    /// See [`Outputs::radiance`].
    pub radiance: ImageHandle,
    /// See [`SurfaceImages`]; 1x1 placeholders, never written, when not asked for.
    pub surface: SurfaceImages,
    /// Whether `surface` is written: the value of the shader's `SURFACE_OUTPUTS`.
    pub surface_written: bool,
}

impl Images {
    /// Creates the images, named `<prefix>.radiance` and so on, written by `pass` through their
    /// bindings, and sets `SURFACE_OUTPUTS`; the surface images only at full size when `surface`
    /// is asked for.
    pub fn create(
        pass: &mut ComputePass<'_>,
        prefix: &str,
        (width, height): (u32, u32),
        surface: bool,
    ) -> Self {
        pass.specialize("SURFACE_OUTPUTS", surface);
        let mut image = |name: &str, (w, h): (u32, u32)| {
            pass.create_image(
                &format!("u_{name}"),
                &format!("{prefix}.{name}"),
                ImageDesc::rgba32f(w, h),
            )
        };
        let surface_size = if surface { (width, height) } else { (1, 1) };
        Self {
            radiance: image("radiance", (width, height)),
            surface: SurfaceImages {
                demodulated: image("demodulated", surface_size),
                albedo: image("albedo", surface_size),
                emission: image("emission", surface_size),
            },
            surface_written: surface,
        }
    }

    /// The [`Outputs`] of these images with the pass's counters.
    pub fn with_stats(self, stats: BufferHandle) -> Outputs {
        Outputs {
            radiance: self.radiance,
            surface: self.surface_written.then_some(self.surface),
            stats,
        }
    }
}
