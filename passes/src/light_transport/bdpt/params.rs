//! How many light subpaths a frame traces and how big its light vertex cache is, and the push
//! constants both BDPT passes share (`Params` in `shaders/bdpt/bdpt.glsl`).

use super::Config;
use crate::light_transport::SampleBatch;
use crate::samples_per_pixel::SamplesPerPixel;
use bytemuck::{Pod, Zeroable};

/// Bytes of one cached light vertex (`LightVertex` in `shaders/bdpt/bdpt.glsl`).
pub const LIGHT_VERTEX_BYTES: u64 = 64;

/// Light-pass invocations per dispatch row (the light pass is one-dimensional).
pub const STRIDE: u32 = 4096;

/// How many light subpaths a frame traces and how many cache slots each one has. Light subpath
/// `i` stores its `k`-th vertex in slot `k * light_paths + i` (vertex-major: the stores of a light
/// pass subgroup's subpaths at one bounce fall side by side) and how many it stored at index `i` of
/// the lengths buffer, so the cache's layout does not depend on thread timing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightCache {
    /// Light subpaths traced this frame.
    pub light_paths: u32,
    /// Cache slots per light subpath: the most vertices one stores.
    pub path_vertices: u32,
}

impl LightCache {
    /// Sizes the cache of a frame of `pixels` pixels with `spp` camera samples each and paths of
    /// at most `max_depth` segments. A light subpath stores at most `max_depth - 2` vertices (the
    /// last one is only connected to the camera), so the light subpaths are as many as `config`
    /// asks for but no more than the cache can hold in the worst case: it never overflows.
    pub fn new(config: &Config, pixels: u32, spp: SamplesPerPixel, max_depth: u32) -> Self {
        let samples = u64::from(pixels) * u64::from(spp.get());
        let wanted = samples * u64::from(config.light_paths_per_sample);
        let per_path = u64::from(max_depth.saturating_sub(2));
        let budget = config.cache_bytes / LIGHT_VERTEX_BYTES;
        let light_paths = if max_depth < 2 {
            0
        } else {
            budget
                .checked_div(per_path)
                .map_or(wanted, |n| wanted.min(n))
        };
        Self {
            light_paths: light_paths.min(u64::from(u32::MAX / 2)) as u32,
            path_vertices: per_path as u32,
        }
    }

    /// Cache slots in all.
    fn slots(&self) -> u64 {
        u64::from(self.light_paths) * u64::from(self.path_vertices)
    }

    /// Bytes of the light vertex cache buffer (never empty).
    pub fn cache_bytes(&self) -> u64 {
        (self.slots() * LIGHT_VERTEX_BYTES).max(LIGHT_VERTEX_BYTES)
    }

    /// Bytes of the cached vertices' base colours (8 per vertex, beside the cache) when textures
    /// or vertex colours make them vary (`colored`), else one unread element.
    pub fn color_bytes(&self, colored: bool) -> u64 {
        if colored {
            (self.slots() * 8).max(8)
        } else {
            8
        }
    }

    /// Bytes of the buffer of light subpath lengths (never empty).
    pub fn lengths_bytes(&self) -> u64 {
        u64::from(self.light_paths).max(1) * 4
    }
}

/// Mirrors `Params` in `shaders/bdpt/bdpt.glsl` (push constants, 24 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Params {
    /// Light subpaths traced this frame.
    pub light_paths: u32,
    /// Light-pass invocations per dispatch row.
    pub stride: u32,
    /// Light subpaths per camera sample.
    pub light_ratio: f32,
    /// Pixels per light subpath (scales the light-tracing splats).
    pub splat_scale: f32,
    /// The camera pass's samples in this dispatch (all of them unless set per batch).
    pub batch: SampleBatch,
}

impl Params {
    /// The push constants of a frame of `pixels` pixels with `spp` camera samples each, whose
    /// light subpaths fill `cache`.
    pub fn new(cache: &LightCache, pixels: u32, spp: SamplesPerPixel) -> Self {
        let light_paths = cache.light_paths;
        let samples = u64::from(pixels) * u64::from(spp.get());
        Self {
            light_paths,
            stride: STRIDE,
            light_ratio: (light_paths as f64 / samples as f64) as f32,
            splat_scale: if light_paths == 0 {
                0.0
            } else {
                (f64::from(pixels) / f64::from(light_paths)) as f32
            },
            batch: SampleBatch::whole(spp),
        }
    }

    /// Light-pass threads to dispatch, as `[x, y, 1]`.
    pub fn light_threads(&self) -> [u32; 3] {
        [
            self.light_paths.min(self.stride),
            self.light_paths.div_ceil(self.stride),
            1,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spp(count: u32) -> SamplesPerPixel {
        SamplesPerPixel::new(count).unwrap()
    }

    #[test]
    fn one_light_path_per_sample_when_it_fits() {
        let cache = LightCache::new(&Config::default(), 64 * 64, spp(4), 8);
        assert_eq!(cache.light_paths, 64 * 64 * 4);
        assert_eq!(cache.path_vertices, 6);
        assert_eq!(cache.cache_bytes(), 64 * 64 * 4 * 6 * LIGHT_VERTEX_BYTES);
        assert_eq!(cache.lengths_bytes(), 64 * 64 * 4 * 4);
        let p = Params::new(&cache, 64 * 64, spp(4));
        assert_eq!(p.light_paths, 64 * 64 * 4);
        assert_eq!(p.light_ratio, 1.0);
        assert_eq!(p.splat_scale, 0.25);
        assert_eq!(p.light_threads(), [4096, 4, 1]);
    }

    #[test]
    fn the_cache_budget_limits_light_paths() {
        let config = Config {
            cache_bytes: 6 * 64 * 1000,
            ..Config::default()
        };
        let cache = LightCache::new(&config, 1920 * 1080, SamplesPerPixel::ONE, 8);
        assert_eq!(cache.light_paths, 1000);
        assert!(cache.cache_bytes() <= config.cache_bytes);
    }

    #[test]
    fn no_light_paths_below_two_segments() {
        let cache = LightCache::new(&Config::default(), 16, SamplesPerPixel::ONE, 1);
        let p = Params::new(&cache, 16, SamplesPerPixel::ONE);
        assert_eq!((p.light_paths, p.splat_scale), (0, 0.0));
        assert_eq!(cache.cache_bytes(), LIGHT_VERTEX_BYTES);
    }
}
