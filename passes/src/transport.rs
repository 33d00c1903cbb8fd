//! What every light-transport pass (path tracing, bidirectional path tracing, ...) produces for a
//! frame, so that accumulation and the denoisers work with any of them.

use lucid_engine::graph::{Access, BufferHandle, ImageHandle, PassBuilder};
use lucid_engine::memory::ImageDesc;

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
