//! The SVGF parameters and when the denoiser runs.

/// When the denoiser runs and on what.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SvgfMode {
    /// Full SVGF on each frame's noisy radiance: temporal accumulation with reprojection and
    /// temporal gradients, variance estimation, a-trous filtering.
    Temporal,
    /// The a-trous filter alone on every frame's output (accumulated while still; with
    /// accumulation off this is the per-frame baseline, which flickers).
    EveryFrame,
    /// The a-trous filter on the accumulated image once it holds this many samples per pixel.
    AfterSamples(u32),
    /// The a-trous filter on the accumulated image once accumulation has run this many seconds.
    AfterSeconds(f32),
}

/// SVGF's parameters (Schied et al. 2017, with A-SVGF's temporal gradients, Schied et al. 2018).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SvgfParams {
    /// When the denoiser runs.
    pub mode: SvgfMode,
    /// A-trous iterations (step sizes 1, 2, 4, ...).
    pub iterations: u32,
    /// Weight of the new frame in the colour's moving average once the history is long.
    pub alpha: f32,
    /// Weight of the new frame in the luminance moments' moving average.
    pub moments_alpha: f32,
    /// Weight of the new frame in the moving averages of the first hits' albedo and emission,
    /// which re-modulate the filtered illumination (lower: steadier edges under motion; the
    /// temporal gradient still resets them where emission changes).
    pub surface_alpha: f32,
    /// Depth edge stopping (larger tolerates more depth difference).
    pub sigma_z: f32,
    /// Normal edge stopping: the exponent of the normals' cosine.
    pub sigma_n: f32,
    /// Luminance edge stopping, in standard deviations of the luminance.
    pub sigma_l: f32,
    /// Clamp fireflies: a sample may be at most [`SvgfParams::firefly_headroom`] times as bright
    /// as the brightest history pixel of the same surface around it (and enters the moments
    /// clamped too), unless it is at most that many times as bright as the second brightest
    /// neighbouring sample of this frame on the same object (light that just appeared lights
    /// several); in a pixel's first frame, only the latter bound holds. A 1-spp path that finds a
    /// light through a rare caustic would otherwise stay a bright spot for many frames, and its
    /// variance would open the luminance edge stopping around it. The price is that light
    /// sampled that rarely is lost (`tests/tests/svgf_fireflies.rs`).
    pub firefly_clamp: bool,
    /// How many times brighter than its neighbours (in the history and in this frame) the firefly
    /// clamp lets a sample be. 32 holds `caustics` and `covered-light` free of blotches over 32
    /// still frames at every seed tested on lavapipe (`training/README.md`, thirty-second
    /// session); 64 let a caustic's firefly through.
    pub firefly_headroom: f32,
    /// Reject history where the temporal gradient shows that shading changed (A-SVGF).
    pub gradients: bool,
    /// Side in pixels of the strata that get one replayed gradient sample each (A-SVGF uses 3; 4
    /// measured as good on the disocclusion and light tests, and keeps more of a changed frame's
    /// samples fresh).
    pub gradient_stratum: u32,
    /// Replay gradient paths every frame, not only after the scene changed (in a static scene the
    /// gradients are exactly zero, which `tests/tests/svgf_history.rs` checks with this set).
    pub gradients_every_frame: bool,
}

impl Default for SvgfParams {
    fn default() -> Self {
        Self {
            mode: SvgfMode::Temporal,
            iterations: 5,
            alpha: 0.2,
            moments_alpha: 0.2,
            surface_alpha: 0.1,
            sigma_z: 1.0,
            sigma_n: 128.0,
            sigma_l: 4.0,
            firefly_clamp: true,
            firefly_headroom: 32.0,
            gradients: true,
            gradient_stratum: 4,
            gradients_every_frame: false,
        }
    }
}
