//! Bidirectional path tracing with a light vertex cache (Davidovic et al. 2014, "Progressive Light
//! Transport Simulation on the GPU"), in two passes:
//!
//! - **light** (`shaders/bdpt/light.comp`): light subpaths from emitters picked by power (their
//!   starts stratified, so that neighbouring invocations trace alike), each stored vertex by
//!   vertex in a light vertex cache ([`LightCache`]) and connected to the camera (light tracing,
//!   its shadow rays leaving from the camera), whose contributions are splatted with 64-bit
//!   fixed-point atomics;
//! - **camera** (`shaders/bdpt/camera.comp`): camera subpaths with emission hits, next-event
//!   estimation and connections to cached light vertices (a light subpath drawn uniformly, then
//!   one of its vertices), all combined with SmallVCM's recursive MIS weights; adds the splats and
//!   writes the frame's radiance; one dispatch per batch of camera samples
//!   ([`crate::light_transport::sample_batches`]). With one sample a pixel, the camera subpaths
//!   Russian roulette keeps past their first segments are parked and continued over a compacted
//!   list (`shaders/bdpt/camera_long.comp`, [`Config::park_depth`]), as the path tracer's.
//!
//! Neither the cache's layout nor the splat sums depend on thread timing, so a frame repeats bit
//! for bit, as the path tracer's does.
//!
//! The sun and the environment emit no light subpaths: the paths they light are found by the
//! camera subpaths' BSDF sampling and NEE, weighted between the two as the path tracer does. Light
//! tracing needs a pinhole camera; with a lens its strategy is dropped from the weights.

mod params;

pub use params::{LightCache, Params, LIGHT_VERTEX_BYTES};

use crate::light_transport::{parking, sample_batches, Frame, Images, Outputs};
use crate::plumbing::scene_buffers::SceneHandles;
use crate::samples_per_pixel::SamplesPerPixel;
use crate::shaders::bdpt::{CAMERA, CAMERA_LONG, LIGHT};
use lucid_engine::graph::{BufferHandle, ComputePass, PassContext, RenderGraph};
use lucid_engine::scene::SceneFeatures;
use lucid_engine::shader::{SpecValue, Specialization};
use lucid_engine::EngineError;
use std::num::NonZeroU32;

/// The multiple-importance-sampling heuristic combining the strategies.
///
/// ```
/// use lucid_passes::light_transport::bdpt::MisHeuristic;
/// assert_eq!(MisHeuristic::ALL.map(MisHeuristic::short_name), ["power", "balance"]);
/// assert_eq!(MisHeuristic::default(), MisHeuristic::Power);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MisHeuristic {
    /// Balance heuristic (SmallVCM's choice).
    Balance,
    /// Power heuristic with exponent 2 (the path tracer's choice).
    #[default]
    Power,
}

impl MisHeuristic {
    /// Both heuristics, in the order menus and the command line list them.
    pub const ALL: [MisHeuristic; 2] = [MisHeuristic::Power, MisHeuristic::Balance];

    /// The name on the command line (`power`, `balance`).
    pub fn short_name(self) -> &'static str {
        match self {
            MisHeuristic::Power => "power",
            MisHeuristic::Balance => "balance",
        }
    }

    /// The name shown in user interfaces.
    pub fn label(self) -> &'static str {
        match self {
            MisHeuristic::Power => "power heuristic",
            MisHeuristic::Balance => "balance heuristic",
        }
    }
}

/// Connection roulette's default threshold: on `classroom`, 40% fewer connections traced (counted on
/// lavapipe) and BDPT's camera pass 4.1% faster at 1080p on an H200, for 0.3% more error at equal
/// samples; light tracing's roulette at this weight took 5.5% off its light pass, for no error
/// measurable at equal samples (bench/README.md).
pub const DEFAULT_CONNECTION_ROULETTE: f32 = 0.1;

/// BDPT tuning.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    /// Light subpaths per camera sample (fewer when the cache budget cannot hold them).
    pub light_paths_per_sample: u32,
    /// Cached light vertices each camera vertex connects to (`Settings::bdpt_connections`).
    pub connections: NonZeroU32,
    /// The MIS heuristic (`Settings::bdpt_mis`).
    pub heuristic: MisHeuristic,
    /// Connection roulette's threshold as a share of what the camera subpath has gathered, and
    /// (up to 1) as the MIS weight under which light tracing's camera connections are rouletted
    /// (`Settings::bdpt_connection_roulette`; 0: off).
    pub connection_roulette: f32,
    /// Whether next-event estimation's shadow ray waits for the first connection's and the two
    /// are walked together (`PAIRED_SHADOW_RAYS` in `shaders/bdpt/bdpt.glsl`; the renderer asks
    /// [`pairs_shadow_rays`]). The image is the same either way with connection roulette off.
    pub pair_shadow_rays: bool,
    /// Most bytes the light vertex cache may take; 128 MiB is the storage-buffer range every
    /// Vulkan device supports.
    pub cache_bytes: u64,
    /// With one sample a pixel, camera subpaths still alive after this many segments are parked
    /// and continued by a second kernel over a compacted list; `None`, or with more samples a
    /// pixel or more pixels than 1920x1080 (128 MiB of parked subpaths), one kernel traces every
    /// camera subpath to its end.
    pub park_depth: Option<u32>,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            light_paths_per_sample: 1,
            connections: NonZeroU32::MIN,
            heuristic: MisHeuristic::Power,
            connection_roulette: DEFAULT_CONNECTION_ROULETTE,
            pair_shadow_rays: true,
            cache_bytes: 128 << 20,
            park_depth: None,
        }
    }
}

impl Config {
    /// `connection_roulette` where it is finite and positive, else 0 (off).
    fn roulette_threshold(&self) -> f32 {
        let share = self.connection_roulette;
        if share.is_finite() && share > 0.0 {
            share
        } else {
            0.0
        }
    }
}

/// Whether BDPT's camera pass should walk next-event estimation's shadow ray together with the
/// first connection's ([`Config::pair_shadow_rays`]) in a scene with `features`: where light
/// subpaths start (emitting surfaces or point lights: without them there are no connections to
/// pair) and without analytic spheres. Holding the waiting ray costs registers (72 to 96 on
/// `classroom`), which the pairing won back and more on `classroom` (-4.1% camera pass on an H200)
/// and the Cornell box (-2.6%), evenly on `cornell-teapot`, but not on `blinds-room` (+7.4%: sky
/// and sun only), `caustics` (+11%) or `covered-light` (+1.3%), the two scenes with spheres, whose
/// tests come one by one before the pair's walk (bench/README.md).
pub fn pairs_shadow_rays(features: &SceneFeatures) -> bool {
    (features.emissive || features.delta_lights) && !features.spheres
}

/// Adds the light and camera passes, reading the scene and the frame constants; the outputs are
/// those of the path tracer.
pub fn add_bdpt(
    g: &mut RenderGraph,
    scene: &SceneHandles,
    frame_constants: BufferHandle,
    spec: &Specialization,
    frame: Frame,
    config: &Config,
) -> Outputs {
    let (width, height, surface) = (frame.width, frame.height, frame.surface);
    let light_cache = LightCache::new(
        config,
        width * height,
        frame.samples_per_pixel,
        frame.max_depth,
    );
    let params = Params::new(&light_cache, width * height, frame.samples_per_pixel);
    let spec = spec
        .clone()
        .set("MIS_POWER", config.heuristic == MisHeuristic::Power)
        .set("CONNECTIONS", config.connections.get())
        .set("CONNECTION_ROULETTE", config.roulette_threshold())
        .set("PAIRED_SHADOW_RAYS", config.pair_shadow_rays);
    let stats = crate::plumbing::stats::add_counter(g, "bdpt.stats");
    let splat = crate::plumbing::stats::add_zeroed(
        g,
        "bdpt.splat",
        u64::from(width * height) * SPLAT_BYTES_PER_PIXEL,
    );

    let mut pass = g.compute_pass("bdpt.light", &LIGHT);
    scene.read(&mut pass);
    pass.read("b_frame", frame_constants);
    let cache = pass.create_buffer("b_lvc", "bdpt.cache", light_cache.cache_bytes());
    let lengths = pass.create_buffer(
        "b_lvc_lengths",
        "bdpt.cache_lengths",
        light_cache.lengths_bytes(),
    );
    // `LVC_COLORS` in `shaders/bdpt/bdpt.glsl`: the cached vertices' base colours.
    let colored = ["HAS_TEXTURES", "HAS_VERTEX_COLORS"]
        .iter()
        .any(|&feature| spec.get(feature) == Some(SpecValue::Bool(true)));
    let colors = pass.create_buffer(
        "b_lvc_colors",
        "bdpt.cache_colors",
        light_cache.color_bytes(colored),
    );
    let splat = pass.read_write("b_splat", splat);
    let stats = pass.read_write("b_stats", stats);
    pass.specialization(&spec)
        .specialize(
            "LIGHT_TRACING_ROULETTE",
            config.roulette_threshold().min(1.0),
        )
        .push(&params)
        .require(require_int64_atomics);
    pass.dispatch(params.light_threads());

    let parking = parking::Parking::clear(g, "bdpt.camera", config.park_depth, &frame);
    let mut pass = g.compute_pass("bdpt.camera", &CAMERA);
    scene.read(&mut pass);
    pass.read("b_frame", frame_constants)
        .read("b_lvc", cache)
        .read("b_lvc_lengths", lengths)
        .read("b_lvc_colors", colors)
        .read("b_splat", splat);
    let stats = pass.read_write("b_stats", stats);
    let images = Images::create(&mut pass, "bdpt", (width, height), surface);
    pass.create_buffer(
        "b_rng_state",
        "bdpt.rng_state",
        u64::from(width * height) * 4,
    );
    let one_sample = frame.samples_per_pixel == SamplesPerPixel::ONE;
    pass.specialization(&spec)
        .specialize("ONE_SAMPLE", one_sample);
    let parked = parking::bind(&mut pass, "bdpt.camera", parking);
    let pushes = sample_batches(frame.samples_per_pixel)
        .into_iter()
        .map(|batch| Params { batch, ..params })
        .collect();
    pass.dispatch_each([width, height, 1], pushes);
    let (images, stats) = match parked {
        Some(parked) => {
            let inputs = |pass: &mut ComputePass<'_>| {
                scene.read(pass);
                pass.specialization(&spec)
                    .read("b_frame", frame_constants)
                    .read("b_lvc", cache)
                    .read("b_lvc_lengths", lengths)
                    .read("b_lvc_colors", colors)
                    .push(&params);
            };
            parking::add_continuation(g, &CAMERA_LONG, inputs, parked, (images, stats))
        }
        None => (images, stats),
    };
    images.with_stats(stats)
}

/// Fails on a device without the 64-bit buffer atomics the light pass splats with.
fn require_int64_atomics(ctx: &PassContext<'_>) -> lucid_engine::Result<()> {
    let info = ctx.context().info();
    if info.int64_atomics {
        return Ok(());
    }
    Err(EngineError::MissingFeature {
        device: info.name.clone(),
        missing: "64-bit integer buffer atomics (shaderInt64, shaderBufferInt64Atomics), \
                  which bidirectional path tracing splats light paths with"
            .into(),
    })
}

/// Bytes of the light-tracing splats per pixel: RGB in 64-bit fixed point (`splat_fixed` in
/// `shaders/bdpt/bdpt.glsl`).
const SPLAT_BYTES_PER_PIXEL: u64 = 3 * 8;
