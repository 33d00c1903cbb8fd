//! Bidirectional path tracing with a light vertex cache (Davidovic et al. 2014, "Progressive Light
//! Transport Simulation on the GPU"), in two passes:
//!
//! - **light** (`shaders/bdpt/light.comp`): light subpaths from emitters picked by power, each
//!   stored vertex by vertex in its own slots of a light vertex cache and connected to the camera
//!   (light tracing), whose contributions are splatted with 64-bit fixed-point atomics;
//! - **camera** (`shaders/bdpt/camera.comp`): camera subpaths with emission hits, next-event
//!   estimation and connections to cached light vertices (a light subpath drawn uniformly, then
//!   one of its vertices), all combined with SmallVCM's recursive MIS weights; adds the splats and
//!   writes the frame's radiance.
//!
//! Neither the cache's layout nor the splat sums depend on thread timing, so a frame repeats bit
//! for bit, as the path tracer's does.
//!
//! The sun and the environment emit no light subpaths: the paths they light are found by the
//! camera subpaths' BSDF sampling and NEE, weighted between the two as the path tracer does. Light
//! tracing needs a pinhole camera; with a lens its strategy is dropped from the weights.

mod params;

pub use params::{Params, LIGHT_VERTEX_BYTES};

use crate::samples_per_pixel::SamplesPerPixel;
use crate::scene_buffers::SceneHandles;
use crate::shaders::bdpt::{CAMERA, LIGHT};
use crate::transport::{Images, Outputs};
use lucid_engine::graph::{Access, BufferHandle, RenderGraph};
use lucid_engine::shader::Specialization;
use lucid_engine::EngineError;

/// The multiple-importance-sampling heuristic combining the strategies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MisHeuristic {
    /// Balance heuristic (SmallVCM's choice).
    Balance,
    /// Power heuristic with exponent 2 (the path tracer's choice).
    #[default]
    Power,
}

/// BDPT tuning.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    /// Light subpaths per camera sample (fewer when the cache budget cannot hold them).
    pub light_paths_per_sample: u32,
    /// Cached light vertices each camera vertex connects to.
    pub connections: u32,
    /// The MIS heuristic.
    pub heuristic: MisHeuristic,
    /// Most bytes the light vertex cache may take; 128 MiB is the storage-buffer range every
    /// Vulkan device supports.
    pub cache_bytes: u64,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            light_paths_per_sample: 1,
            connections: 1,
            heuristic: MisHeuristic::Power,
            cache_bytes: 128 << 20,
        }
    }
}

/// The image and sampling of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Camera samples per pixel.
    pub samples_per_pixel: SamplesPerPixel,
    /// Longest path in segments (Mitsuba's convention).
    pub max_depth: u32,
    /// Write the denoiser's images too ([`crate::transport::SurfaceImages`]).
    pub surface: bool,
}

/// Adds the light and camera passes, reading the scene and the frame constants; the outputs are
/// those of the path tracer.
pub fn add(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    frame_constants: BufferHandle,
    spec: &Specialization,
    frame: Frame,
    config: &Config,
) -> Outputs {
    let (width, height, surface) = (frame.width, frame.height, frame.surface);
    let params = Params::new(
        config,
        width * height,
        frame.samples_per_pixel,
        frame.max_depth,
    );
    let spec = spec
        .clone()
        .set("MIS_POWER", config.heuristic == MisHeuristic::Power);
    let stats = crate::stats::add_counter(g, "bdpt.stats");
    let splat = add_splat_clear(g, u64::from(width * height) * SPLAT_BYTES_PER_PIXEL);

    let mut p = g.add_pass("bdpt.light");
    scene.read(&mut p);
    let constants = p.read(frame_constants, Access::ComputeRead);
    let cache = p.create_buffer("bdpt.cache", params.cache_bytes());
    let cache = p.write(cache, Access::ComputeWrite);
    let lengths = p.create_buffer("bdpt.cache_lengths", params.lengths_bytes());
    let lengths = p.write(lengths, Access::ComputeWrite);
    let splat = p.write(splat, Access::ComputeReadWrite);
    let stats = p.write(stats, Access::ComputeReadWrite);
    let (light_scene, light_spec) = (*scene, spec.clone());
    p.execute(move |ctx| {
        let info = ctx.context().info();
        if !info.int64_atomics {
            return Err(EngineError::MissingFeature {
                device: info.name.clone(),
                missing: "64-bit integer buffer atomics (shaderInt64, shaderBufferInt64Atomics), \
                          which bidirectional path tracing splats light paths with"
                    .into(),
            });
        }
        let dispatch = ctx
            .compute(&LIGHT)
            .specialization(&light_spec)
            .push(&params)
            .buffer("b_frame", constants)
            .buffer("b_stats", stats)
            .buffer("b_lvc", cache)
            .buffer("b_lvc_lengths", lengths)
            .buffer("b_splat", splat);
        light_scene
            .bind(dispatch)
            .dispatch_threads(params.light_threads())
    });

    let mut p = g.add_pass("bdpt.camera");
    scene.read(&mut p);
    let constants = p.read(frame_constants, Access::ComputeRead);
    let cache = p.read(cache, Access::ComputeRead);
    let lengths = p.read(lengths, Access::ComputeRead);
    let splat = p.read(splat, Access::ComputeRead);
    let stats = p.write(stats, Access::ComputeReadWrite);
    let images = Images::create(&mut p, "bdpt", (width, height), surface);
    let scene = *scene;
    p.execute(move |ctx| {
        let dispatch = ctx
            .compute(&CAMERA)
            .specialization(&spec)
            .push(&params)
            .buffer("b_frame", constants)
            .buffer("b_stats", stats)
            .buffer("b_lvc", cache)
            .buffer("b_lvc_lengths", lengths)
            .buffer("b_splat", splat);
        scene
            .bind(images.bind(dispatch))
            .dispatch_threads([width, height, 1])
    });
    images.with_stats(stats)
}

/// Bytes of the light-tracing splats per pixel: RGB in 64-bit fixed point (`splat_fixed` in
/// `shaders/bdpt/bdpt.glsl`).
const SPLAT_BYTES_PER_PIXEL: u64 = 3 * 8;

/// Adds a pass creating the zeroed light-tracing splat buffer.
fn add_splat_clear(g: &mut RenderGraph, bytes: u64) -> BufferHandle {
    let mut p = g.add_pass("bdpt.splat.clear");
    let splat = p.create_buffer("bdpt.splat", bytes);
    let splat = p.write(splat, Access::TransferWrite);
    p.execute(move |ctx| ctx.fill_buffer(splat, 0));
    splat
}
