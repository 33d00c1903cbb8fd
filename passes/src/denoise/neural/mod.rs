//! The learned temporal denoiser: a recurrent U-Net autoencoder (after Chaitanya et al. 2017)
//! trained on Lucid's own frames (`training/`), run in Vulkan compute (`shaders/neural/`).
//!
//! Per frame:
//! 1. **Inputs** ([`FrameInputs`]): the light transport's surface images and the G-buffer's, read
//!    where they are used (`shaders/neural/inputs.glsl`). Where a frame's inputs are read back
//!    (`lucid dataset`, image denoisers' albedo and normal), [`add_record`] gathers them into one
//!    planar float buffer (`shaders/neural/record.glsl`); inference does not read it.
//! 2. **Features**: log radiance, albedo, normal, roughness, log depth, last frame's output
//!    reprojected by the motion vectors where depth and normal say the surface is the same, the
//!    reprojection mask, and two running means of the noisy radiance reprojected with the same
//!    taps (as SVGF accumulates it: log mean, history length, log standard deviation of luminance;
//!    and of the radiance range-compressed against fireflies): 24 half-precision channels; for the
//!    kernel decoder also the radiance pooled to each of its coarser scales.
//! 3. **Network**: 3x3 convolutions at full, half and quarter resolution with skip connections
//!    ([`Widths::unet`]: the widths are the weights file's), fused bias and ReLU, average pooling down and nearest upsampling up (read in
//!    place by the next convolution); on the tensor cores where the device has them, else portable
//!    compute ([`InferencePath`]).
//! 4. **Decoder** ([`Decoder`]): either one output layer predicting log radiance directly, or
//!    one a scale ([`KERNEL_HEADS`], three to five as the weights have them) predicting per-pixel
//!    5x5 kernels that filter the noisy log radiance at full, half, quarter (eighth, sixteenth)
//!    resolution, composited coarse to fine (`shaders/neural/kernel*`; the full scale is filtered
//!    and composited in the output pass, `output.comp`).
//! 5. **Output**: the predicted log radiance blended with the reprojected history by a learned
//!    per-pixel weight (only where the mask allows), kept as the next frame's history, and
//!    re-modulated by the first hits' albedo plus emission averaged over time (reprojected with
//!    those of the running means' taps that saw the same object, the G-buffer's object id; each
//!    frame's samples are jittered over the pixel, so one frame's would make texture, emitter and
//!    object edges flicker; `training/model.py`, `antialias_surface`).
//! 6. **Gated filter** (weights with `atrous_steps` metadata, as the committed ones are, unless
//!    [`NeuralParams::gated_filter`] turns it off): before the re-modulation, the output's
//!    illumination filtered by edge-aware a-trous steps and blended back per pixel by a gate the
//!    network predicts (`shaders/neural/atrous_step.glsl`); the history keeps the unfiltered output.
//!
//! The history (last output, surface, running means and second moments, averaged albedo and
//! emission) is the render graph's
//! keyed temporal images under a per-denoiser prefix, so two denoisers in one graph keep their own;
//! a resize, a scene change or
//! [`Executor::reset_history`](lucid_engine::graph::Executor::reset_history) starts afresh.
//! `training/model.py` is the reference of every step; `tests/neural_parity.rs` checks this
//! implementation against it.

mod network;
mod params;
mod weights;

pub use network::{InferencePath, Network};
pub use params::NeuralParams;
pub use weights::{
    Decoder, Layer, NetworkWeights, WeightsError, Widths, ATROUS_MAX_SPACING, ATROUS_MAX_STEPS,
    BUILTIN, EMISSION_MOTION, FEATURES, FORMAT, HIDDEN, HISTORY_FRAMES, KERNEL_HEADS,
    KERNEL_SCALES, KERNEL_TAPS, SPATIAL_VARIANCE_FRAMES,
};

use crate::denoise::atrous_tile;
use crate::denoise::gbuffer::GBuffer;
use crate::denoise::handoff::{self, Handoff};
use crate::denoise::{DenoiseInputs, Denoised, FrameDenoiser, FrameInfo, TransportRequest};
use crate::light_transport::SurfaceImages;
use crate::shaders::neural::{
    ATROUS_LAST, ATROUS_STEP, CONV, CONV_COOP, FEATURES as FEATURES_SHADER, KERNEL_FILTER, OUTPUT,
    OUTPUT_ATROUS, POOL, RADIANCE_POOL, RECORD,
};
use ash::vk;
use lucid_engine::capture::ImageData;
use lucid_engine::graph::{BufferHandle, ComputePass, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::{EngineError, Result};

/// Channels of a pixel's record (`RECORD_SIZE` in `shaders/neural/record.glsl`).
pub const RECORD_CHANNELS: u32 = 17;

/// The plane after a read-back record's channels: each pixel's object id, its low 24 bits as a
/// float (`RECORD_OBJECT` in the shader).
pub const RECORD_OBJECT: u32 = RECORD_CHANNELS;

/// The first channel of the first hit's albedo in a record (`RECORD_ALBEDO` in the shader).
pub const RECORD_ALBEDO: u32 = 3;
/// The first channel of the emission seen first in a record (`RECORD_EMISSION` in the shader).
pub const RECORD_EMISSION: u32 = 6;
/// The first channel of the G-buffer normal in a record (`RECORD_NORMAL` in the shader).
pub const RECORD_NORMAL: u32 = 9;

/// Three channels of a read-back record from `first` on, as an RGB image (alpha 1): e.g. the
/// albedo and normal images that image denoisers take besides the radiance.
pub fn record_image(record: &[u8], (width, height): (u32, u32), first: u32) -> Result<ImageData> {
    let plane = width as usize * height as usize;
    if record.len() as u64 != record_bytes(width, height) || first + 3 > RECORD_CHANNELS {
        return Err(EngineError::InvalidArgument(format!(
            "a {width}x{height} record has {} bytes and {RECORD_CHANNELS} channels, not {} bytes and channel {first}..{}",
            record_bytes(width, height),
            record.len(),
            first + 3
        )));
    }
    let floats: Vec<f32> = bytemuck::pod_collect_to_vec(record);
    let value = |c: usize, i: usize| floats[c * plane + i];
    let first = first as usize;
    let pixels = (0..plane)
        .map(|i| {
            [
                value(first, i),
                value(first + 1, i),
                value(first + 2, i),
                1.0,
            ]
        })
        .collect();
    ImageData::from_pixels(width, height, pixels)
        .map_err(|e| EngineError::InvalidArgument(e.to_string()))
}

/// Bytes of the record buffer of a `width` x `height` frame: its channels and the object ids.
pub fn record_bytes(width: u32, height: u32) -> u64 {
    u64::from(RECORD_CHANNELS + 1) * u64::from(width) * u64::from(height) * 4
}

/// The learned denoiser as the renderer's denoiser: the network, what runs of it and its history
/// prefix. It runs every frame on the frame's own radiance, and starts afresh when the scene
/// changes (its history describes the old scene).
#[derive(Clone)]
pub struct NeuralDenoiser {
    network: Network,
    params: NeuralParams,
    prefix: String,
}

impl NeuralDenoiser {
    /// The denoiser running `network` as `params` choose, its history under `prefix`.
    pub fn new(network: Network, params: NeuralParams, prefix: &str) -> Self {
        Self {
            network,
            params,
            prefix: prefix.to_owned(),
        }
    }

    /// Changes what runs from the next frame on; the history is kept (it does not depend on them).
    pub fn set_params(&mut self, params: NeuralParams) {
        self.params = params;
    }
}

impl FrameDenoiser for NeuralDenoiser {
    fn plan(&mut self, _frame: &FrameInfo) -> Option<TransportRequest> {
        Some(TransportRequest::default())
    }

    fn add(&mut self, g: &mut RenderGraph, inputs: &DenoiseInputs) -> Denoised {
        let size = (inputs.width, inputs.height);
        let frame = FrameInputs::new(&inputs.surface, &inputs.gbuffer);
        let denoised = add_neural(g, &self.network, self.params, &frame, size, &self.prefix);
        let denoised = denoised.radiance;
        Denoised {
            image: handoff::add_handoff(g, inputs, denoised, &self.prefix, Handoff::NEURAL),
            gradient: None,
            // Culled unless read back.
            record: Some(add_record(g, &frame, size)),
        }
    }

    fn reset_on_scene_change(&self) -> Vec<String> {
        let mut keys = HistoryKeys::new(&self.prefix).all();
        keys.push(handoff::history_key(&self.prefix));
        keys
    }
}

/// The images the learned denoiser reads of a frame, each channel of a record
/// (`shaders/neural/inputs.glsl`) and the object ids (which records lack): the light transport's
/// surface images and the G-buffer's, or a test's uploads.
#[derive(Clone, Copy, Debug)]
pub struct FrameInputs {
    /// The demodulated radiance (rgb), `rgba32f`.
    pub demodulated: ImageHandle,
    /// The first hit's albedo (rgb), `rgba32f`.
    pub albedo: ImageHandle,
    /// The radiance the first hit emits towards the camera (rgb), `rgba32f`.
    pub emission: ImageHandle,
    /// The G-buffer normal (xyz) and roughness (w), `rgba16f`.
    pub normal_roughness: ImageHandle,
    /// The view-space depth (0 for the sky), `r32f`.
    pub depth: ImageHandle,
    /// The offset to last frame's pixel (xy) and last frame's depth of the point (z), `rgba16f`.
    pub motion: ImageHandle,
    /// The G-buffer's ids (object, material, primitive, hit flag), `rgba32ui`.
    pub ids: ImageHandle,
}

impl FrameInputs {
    /// A frame's inputs from the light transport's `surface` images and the G-buffer.
    pub fn new(surface: &SurfaceImages, gbuffer: &GBuffer) -> Self {
        Self {
            demodulated: surface.demodulated,
            albedo: surface.albedo,
            emission: surface.emission,
            normal_roughness: gbuffer.normal_roughness,
            depth: gbuffer.depth,
            motion: gbuffer.motion,
            ids: gbuffer.ids,
        }
    }

    /// Binds the images to a pass whose shader includes `shaders/neural/inputs.glsl`.
    fn read(&self, p: &mut ComputePass<'_>) {
        p.read("u_demodulated", self.demodulated)
            .read("u_albedo", self.albedo)
            .read("u_emission", self.emission)
            .read("u_normal_roughness", self.normal_roughness)
            .read("u_depth", self.depth)
            .read("u_motion", self.motion);
    }
}

/// Adds the pass gathering a frame's `inputs` into a record; returns the record buffer (see
/// [`record_bytes`]). Inference does not read it: the pass runs where the record is read back.
pub fn add_record(
    g: &mut RenderGraph,
    inputs: &FrameInputs,
    (width, height): (u32, u32),
) -> BufferHandle {
    let mut p = g.compute_pass("neural.record", &RECORD);
    inputs.read(&mut p);
    p.read("u_ids", inputs.ids);
    let record = p.create_buffer("b_record", "neural.record", record_bytes(width, height));
    p.dispatch([width, height, 1]);
    record
}

/// The history keys of a denoiser instance named `prefix`.
struct HistoryKeys {
    output: String,
    surface: String,
    accum: String,
    moment: String,
    robust: String,
    albedo: String,
    emission: String,
}

impl HistoryKeys {
    fn new(prefix: &str) -> Self {
        let key = |name: &str| format!("{prefix}.{name}");
        Self {
            output: key("output"),
            surface: key("surface"),
            accum: key("accum"),
            moment: key("moment"),
            robust: key("robust"),
            albedo: key("albedo"),
            emission: key("emission"),
        }
    }

    /// Every key.
    fn all(self) -> Vec<String> {
        vec![
            self.output,
            self.surface,
            self.accum,
            self.moment,
            self.robust,
            self.albedo,
            self.emission,
        ]
    }
}

/// The network's weights in a frame's graph: float32 (biases, and the portable path's weights) and,
/// on the tensor-core path, half precision (each layer's offset in uvec4s is the network's).
struct WeightHandles {
    full: BufferHandle,
    half: Option<BufferHandle>,
}

/// What [`add_neural`] adds to the graph that callers read.
#[derive(Clone, Copy, Debug)]
pub struct NeuralImages {
    /// The denoised radiance (`rgba32f`).
    pub radiance: ImageHandle,
    /// This frame's running mean of the demodulated radiance (rgb) and its history length (a),
    /// `rgba32f`: the `<prefix>.accum` history as written this frame.
    pub accum: ImageHandle,
    /// This frame's running second moment of the demodulated radiance's luminance (`r32f`): the
    /// `<prefix>.moment` history as written this frame.
    pub moment: ImageHandle,
    /// This frame's running mean of the range-compressed demodulated radiance (rgb) and the second
    /// moment of its luminance (a), `rgba32f`: the `<prefix>.robust` history as written this frame.
    pub robust: ImageHandle,
}

/// A half-precision activation tensor of the network.
#[derive(Clone, Copy)]
struct Tensor {
    buffer: BufferHandle,
    channels: u32,
    size: (u32, u32),
}

/// Push constants of `features.comp`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FeaturesParams {
    width: u32,
    height: u32,
    /// 0 on the first frame and after a reset: nothing is reprojected.
    history_valid: u32,
    /// [`NetworkWeights::emission_motion`].
    emission_motion: f32,
    /// [`NetworkWeights::history_frames`].
    history_frames: f32,
    /// [`NetworkWeights::spatial_variance_frames`].
    spatial_variance_frames: f32,
}

/// Adds the denoiser over the frame's `inputs` at `width` x `height`, with its history under the
/// keys `<prefix>.output`, `<prefix>.surface`, `<prefix>.accum` (running mean and its length),
/// `<prefix>.moment` (second moment of luminance), `<prefix>.robust` (the range-compressed running
/// mean and its second moment), `<prefix>.albedo` and `<prefix>.emission` (the first hits' albedo
/// and log emission averaged over time), running of `network` what `params` choose; returns the
/// denoised radiance and this frame's accumulation.
pub fn add_neural(
    g: &mut RenderGraph,
    network: &Network,
    params: NeuralParams,
    inputs: &FrameInputs,
    (width, height): (u32, u32),
    prefix: &str,
) -> NeuralImages {
    let weights = WeightHandles {
        full: g.import_buffer("neural.weights", network.buffer.clone()),
        half: network
            .half
            .as_ref()
            .map(|(buffer, _)| g.import_buffer("neural.half_weights", buffer.clone())),
    };
    let keys = HistoryKeys::new(prefix);
    // The output's log radiance as the packed halves `pack_channels` rounds it to, exactly: an
    // `rgba16f` image store may truncate (lavapipe's and NVIDIA's do, and NVIDIA's compiler folds
    // the shader's own rounding into the store), which the recurrence would compound frame after
    // frame into a darker output.
    let output_history = g.temporal_image(
        &keys.output,
        ImageDesc::new(width, height, vk::Format::R32G32_UINT),
    );
    let surface_history = g.temporal_image(&keys.surface, ImageDesc::rgba32f(width, height));
    let accum_history = g.temporal_image(&keys.accum, ImageDesc::rgba32f(width, height));
    let moment_history = g.temporal_image(&keys.moment, ImageDesc::r32f(width, height));
    let robust_history = g.temporal_image(&keys.robust, ImageDesc::rgba32f(width, height));
    let albedo_history = g.temporal_image(&keys.albedo, ImageDesc::rgba32f(width, height));
    let emission_history = g.temporal_image(&keys.emission, ImageDesc::rgba32f(width, height));
    let full = (width, height);
    let kernel = network.decoder == Decoder::Kernel;

    let mut p = g.compute_pass(&format!("{prefix}.features"), &FEATURES_SHADER);
    let prev = [
        output_history.prev,
        accum_history.prev,
        moment_history.prev,
        robust_history.prev,
        albedo_history.prev,
        emission_history.prev,
    ];
    let emission_motion = network.emission_motion;
    let history_frames = network.history_frames as f32;
    let spatial_variance_frames = network.spatial_variance_frames as f32;
    inputs.read(&mut p);
    p.read("u_prev_output", prev[0])
        .read("u_ids", inputs.ids)
        .push_with(move |ctx| FeaturesParams {
            width,
            height,
            history_valid: u32::from(prev.iter().all(|&h| ctx.history_valid(h))),
            emission_motion,
            history_frames,
            spatial_variance_frames,
        });
    p.history("u_prev_surface", "u_surface", surface_history);
    let accum = p.history("u_prev_accum", "u_accum", accum_history);
    let moment = p.history("u_prev_moment", "u_moment", moment_history);
    let robust = p.history("u_prev_robust", "u_robust", robust_history);
    let albedo = p.history("u_prev_albedo_mean", "u_albedo_mean", albedo_history);
    let emission = p.history("u_prev_emission_mean", "u_emission_mean", emission_history);
    // The kernel decoder's radiance pooled to each coarser scale the features pass pools, and
    // the eighth's linear means where a sixteenth is pooled from them (16 bytes unwritten where
    // not).
    let levels = if kernel { network.scales - 1 } else { 0 };
    p.specialize("POOLED_LEVELS", levels);
    let mut level_size = full;
    let mut pooled_radiance = Vec::new();
    for (level, scale) in COARSER_SCALES[..FEATURES_POOLED_LEVELS].iter().enumerate() {
        level_size = half_size(level_size);
        let wanted = (level as u32) < levels;
        let bytes = if wanted { vec4_bytes(level_size) } else { 16 };
        let buffer = p.create_buffer(
            &format!("b_radiance_{scale}"),
            "neural.pooled_radiance",
            bytes,
        );
        if wanted {
            pooled_radiance.push(buffer);
        }
    }
    let sixteenth_wanted = levels as usize > FEATURES_POOLED_LEVELS;
    let eighth_linear = p.create_buffer(
        "b_radiance_eighth_linear",
        "neural.pooled_radiance_linear",
        if sixteenth_wanted {
            vec4_bytes(level_size)
        } else {
            16
        },
    );
    let features = Tensor {
        buffer: p.create_buffer(
            "b_features",
            "neural.features",
            tensor_bytes(FEATURES, full),
        ),
        channels: FEATURES,
        size: full,
    };
    p.dispatch([width, height, 1]);
    if sixteenth_wanted {
        pooled_radiance.push(add_radiance_pool(g, eighth_linear, level_size));
    }

    let conv = |g: &mut RenderGraph, layer: usize, in0: Tensor, in1: Option<Tensor>, pool| {
        add_conv(g, network, &weights, layer, (in0, in1), pool)
    };
    let (e0, [p0, _]) = conv(g, 0, features, None, 1);
    let (e1, [p1, _]) = conv(g, 1, p0.expect("pooled"), None, 1);
    let (e2, _) = conv(g, 2, p1.expect("pooled"), None, 0);
    let (bottleneck, _) = conv(g, 3, e2, None, 0);
    let (d1, _) = conv(g, 4, bottleneck, Some(e1), 0);
    let (d0, [d0_half, d0_quarter]) = conv(g, 5, d1, Some(e0), levels.min(2));
    let (net, _) = conv(g, 6, d0, None, 0);
    // The kernel decoder's coarser scales: the decoder features pooled to each (those below the
    // quarter each from the one before), each scale's head, then its filtered radiance;
    // the output pass filters the full scale and composites it with the half scale's filtered
    // radiance and the quarter scale's detail.
    let mut coarse_features: Vec<Tensor> = [d0_half, d0_quarter].into_iter().flatten().collect();
    while let Some(&finer) = coarse_features.last() {
        let level = coarse_features.len();
        if level >= levels as usize {
            break;
        }
        let name = format!("neural.dec0.pool_{}", COARSER_SCALES[level]);
        coarse_features.push(add_pool(g, finer, &name));
    }
    let coarse = (!coarse_features.is_empty()).then(|| {
        let heads: Vec<Tensor> = coarse_features
            .into_iter()
            .enumerate()
            .map(|(level, features)| conv(g, 7 + level, features, None, 0).0)
            .collect();
        let (half_filtered, quarter_detail) =
            add_kernel_scales(g, &pooled_radiance, &heads, network.linear_mix);
        (heads[0], half_filtered, quarter_detail)
    });

    let gated = params.gated_filter && !network.atrous_steps.is_empty();
    let shader = if gated { &OUTPUT_ATROUS } else { &OUTPUT };
    let mut p = g.compute_pass(&format!("{prefix}.output"), shader);
    // The direct decoder has no scales: its output is bound in their place (not read).
    let (half_net, half_filtered, quarter_detail) = coarse.unwrap_or((net, net.buffer, net.buffer));
    p.read("b_features", features.buffer)
        .read("b_net", net.buffer)
        .read("b_half_logits", half_net.buffer)
        .read("b_half_filtered", half_filtered)
        .read("b_quarter_detail", quarter_detail)
        .read("u_albedo_mean", albedo)
        .read("u_emission_mean", emission)
        .specialize("KERNEL", kernel)
        .specialize("NET_CHANNELS", net.channels)
        .specialize("HALF_CHANNELS", half_net.channels)
        .specialize("LINEAR_MIX", network.linear_mix)
        .push(&[width, height]);
    p.write("u_output", output_history.cur);
    let radiance = if gated {
        // The gate is the output layer's last channel (`layers`' seventh is `out`).
        p.specialize("GATE_CHANNEL", network.layers[6].out - 1);
        let illumination = p.create_image(
            "u_illumination",
            &format!("{prefix}.illumination"),
            ImageDesc::rgba32f(width, height),
        );
        p.dispatch([width, height, 1]);
        add_atrous(
            g,
            &network.atrous_steps,
            illumination,
            inputs.normal_roughness,
            (albedo, emission),
            full,
            prefix,
        )
    } else {
        let radiance = p.create_image(
            "u_radiance",
            &format!("{prefix}.radiance"),
            ImageDesc::rgba32f(width, height),
        );
        p.dispatch([width, height, 1]);
        radiance
    };
    NeuralImages {
        radiance,
        accum,
        moment,
        robust,
    }
}

/// Push constants of the gated filter's a-trous steps (`atrous_step.glsl`).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct AtrousStepParams {
    width: u32,
    height: u32,
    /// The taps' spacing in pixels.
    step: u32,
}

/// Adds the gated a-trous filter over the output (`training/model.py`, `atrous`): the output's
/// `illumination` (rgb, its gate in alpha) filtered by one pass per spacing of `steps` (on the
/// tile of [`atrous_tile`], edge-stopped by the G-buffer's `normal_roughness`), the last of which
/// (`atrous_last.comp`) blends its result with the illumination by the gate and re-modulates it by
/// the first hits' `albedo` and `emission` averaged over time, all at `width` x `height`. Returns
/// the denoised radiance.
fn add_atrous(
    g: &mut RenderGraph,
    steps: &[u32],
    illumination: ImageHandle,
    normal_roughness: ImageHandle,
    (albedo, emission): (ImageHandle, ImageHandle),
    (width, height): (u32, u32),
    prefix: &str,
) -> ImageHandle {
    let desc = ImageDesc::rgba32f(width, height);
    let mut filtered = illumination;
    for (index, &step) in steps.iter().enumerate() {
        let last = index + 1 == steps.len();
        let shader = if last { &ATROUS_LAST } else { &ATROUS_STEP };
        let mut p = g.compute_pass(&format!("{prefix}.atrous{index}"), shader);
        p.read("u_in", filtered)
            .read("u_normal_roughness", normal_roughness)
            .push(&AtrousStepParams {
                width,
                height,
                step,
            });
        filtered = if last {
            p.read("u_illumination", illumination)
                .read("u_albedo_mean", albedo)
                .read("u_emission_mean", emission);
            p.create_image("u_radiance", &format!("{prefix}.radiance"), desc)
        } else {
            p.create_image("u_out", &format!("{prefix}.atrous{index}"), desc)
        };
        p.dispatch(atrous_tile::threads(step, (width, height)));
    }
    filtered
}

/// The kernel decoder's scales below full resolution, as its buffers and passes are named.
const COARSER_SCALES: [&str; 4] = ["half", "quarter", "eighth", "sixteenth"];

/// The coarser scales whose radiance the features pass pools within its 8x8 tiles; the sixteenth's
/// is pooled from the eighth's linear means ([`add_radiance_pool`]).
const FEATURES_POOLED_LEVELS: usize = 3;

/// Adds the pass that pools the eighth scale's linear radiance means (`eighth`, `eighth_size`) to
/// the sixteenth scale's log radiance (`radiance_pool.comp`); returns its buffer.
fn add_radiance_pool(
    g: &mut RenderGraph,
    eighth: BufferHandle,
    eighth_size: (u32, u32),
) -> BufferHandle {
    let size = half_size(eighth_size);
    let mut p = g.compute_pass("neural.pool_radiance.sixteenth", &RADIANCE_POOL);
    p.read("b_in", eighth)
        .push(&[size.0, size.1, eighth_size.0, eighth_size.1]);
    let out = p.create_buffer("b_out", "neural.pooled_radiance", vec4_bytes(size));
    p.dispatch([size.0, size.1, 1]);
    out
}

/// Adds the kernel decoder's coarser scales (`training/kernel_model.py`, `KernelOutput`) from their
/// heads' outputs (`heads`, half resolution first) and the log radiance the features pass pooled
/// to them (`radiance`): each scale's log radiance filtered by its per-pixel kernels
/// (`kernel_filter.comp`); the coarsest as the difference it adds to the next finer scale, and each
/// between the coarsest and the half as its own difference with the coarser ones' composited in.
/// Returns the half scale's filtered radiance and the quarter scale's difference, which the output
/// pass composites with the full scale it filters. With `linear_mix` every scale is filtered and
/// composited in linear space too, each buffer holding both results a pixel.
fn add_kernel_scales(
    g: &mut RenderGraph,
    radiance: &[BufferHandle],
    heads: &[Tensor],
    linear_mix: bool,
) -> (BufferHandle, BufferHandle) {
    let results = 1 + u64::from(linear_mix);
    // Scale `index` (0 the half) filtered; a difference from `finer`, with `coarser`'s composited.
    let filter = |g: &mut RenderGraph,
                  index: usize,
                  finer: Option<BufferHandle>,
                  coarser: Option<BufferHandle>| {
        let head = heads[index];
        // The neighbouring scales' sizes, where they are read (else unused).
        let finer_size = finer.map_or(head.size, |_| heads[index - 1].size);
        let coarser_size = coarser.map_or(head.size, |_| heads[index + 1].size);
        let kind = if finer.is_some() { "detail" } else { "filter" };
        let name = format!("neural.kernel_{kind}.{}", COARSER_SCALES[index]);
        let radiance = radiance[index];
        let mut p = g.compute_pass(&name, &KERNEL_FILTER);
        // Buffers a pass does not read are bound as the radiance (not read).
        p.read("b_logits", head.buffer)
            .read("b_radiance", radiance)
            .read("b_finer", finer.unwrap_or(radiance))
            .read("b_coarser", coarser.unwrap_or(radiance))
            .specialize("LOGIT_CHANNELS", head.channels)
            .specialize("DETAIL", finer.is_some())
            .specialize("COARSER", coarser.is_some())
            .specialize("LINEAR_MIX", linear_mix)
            .push(&[
                head.size.0,
                head.size.1,
                finer_size.0,
                finer_size.1,
                coarser_size.0,
                coarser_size.1,
            ]);
        let bytes = results * vec4_bytes(head.size);
        let out = p.create_buffer("b_out", "neural.kernel_filtered", bytes);
        p.dispatch([head.size.0, head.size.1, 1]);
        out
    };
    let coarsest = heads.len() - 1;
    let filtered: Vec<BufferHandle> = (0..coarsest).map(|i| filter(g, i, None, None)).collect();
    let mut detail = filter(g, coarsest, Some(filtered[coarsest - 1]), None);
    for index in (1..coarsest).rev() {
        detail = filter(g, index, Some(filtered[index - 1]), Some(detail));
    }
    (filtered[0], detail)
}

/// Bytes of a float32 vec4 per pixel at `size`.
fn vec4_bytes((width, height): (u32, u32)) -> u64 {
    u64::from(width) * u64::from(height) * 16
}

/// Bytes of a half-precision tensor of `channels` at `size`.
fn tensor_bytes(channels: u32, (width, height): (u32, u32)) -> u64 {
    u64::from(channels) * u64::from(width) * u64::from(height) * 2
}

/// Adds convolution `index` of the network's layers over `in0` then `in1` (the skip connection), at
/// `in1`'s size (`in0` upsampled when smaller) or, without `in1`, at `in0`'s. Returns its output
/// and, for `pool_levels` of 1 or 2, the output 2x2 average-pooled, and that pooled once more
/// (fused into the convolution on the tensor-core path).
fn add_conv(
    g: &mut RenderGraph,
    network: &Network,
    weights: &WeightHandles,
    index: usize,
    (in0, in1): (Tensor, Option<Tensor>),
    pool_levels: u32,
) -> (Tensor, [Option<Tensor>; 2]) {
    let offset = network.offsets[index];
    let layer = &network.layers[index];
    let out_channels = layer.out_padded();
    debug_assert_eq!(in0.channels, layer.in0);
    debug_assert_eq!(in1.map_or(0, |t| t.channels), layer.in1);
    let size = in1.map_or(in0.size, |t| t.size);
    let name = format!("neural.{}", layer.name);
    let shader = match network.path {
        InferencePath::Portable => &CONV,
        InferencePath::TensorCores => &CONV_COOP,
    };
    let mut p = g.compute_pass(&name, shader);
    p.read("b_weights", weights.full)
        .read("b_in0", in0.buffer)
        // Without a second input the first is bound in its place (the shader does not read it).
        .read("b_in1", in1.unwrap_or(in0).buffer)
        .specialize("IN0_CHANNELS", layer.in0)
        .specialize("IN1_CHANNELS", layer.in1)
        .specialize("OUT_CHANNELS", out_channels)
        .specialize("IN0_UPSAMPLED", in0.size != size)
        .specialize("RELU", layer.relu);
    let buffer = p.create_buffer("b_out", &name, tensor_bytes(out_channels, size));
    let output = Tensor {
        buffer,
        channels: out_channels,
        size,
    };
    let push = [size.0, size.1, in0.size.0, in0.size.1];
    match (weights.half, &network.half) {
        (Some(half_weights), Some((_, half_offsets))) => {
            let bias = offset + 9 * layer.inputs() * out_channels / 4;
            let half_offset = half_offsets[index];
            // Workgroups of four subgroups, two rows of 16 pixels each, and up to 32 output
            // channels (64-channel layers in two workgroups): the fastest of the configurations
            // measured on an H100 (`bench/README.md`); a subgroup's two rows share the staged
            // rows their taps read, three rows take too many registers.
            let (subgroups, rows, group_tiles) = (4, 2, 2);
            let tiles = out_channels.div_ceil(16);
            let half = half_size(size);
            let quarter = half_size(half);
            let mut pooled = |level: u32, name: &str, size: (u32, u32)| {
                let wanted = pool_levels >= level;
                let bytes = if wanted {
                    tensor_bytes(out_channels, size)
                } else {
                    16
                };
                let buffer = p.create_buffer(name, "neural.pooled", bytes);
                wanted.then_some(Tensor {
                    buffer,
                    channels: out_channels,
                    size,
                })
            };
            let pooled = [
                pooled(1, "b_pooled", half),
                pooled(2, "b_pooled_twice", quarter),
            ];
            p.read("b_half_weights", half_weights)
                .specialize("ROWS", rows)
                .specialize("POOL_LEVELS", pool_levels)
                .specialize("GROUP_TILES", group_tiles)
                .specialize("local_size_x", 32 * subgroups)
                .push(&[push[0], push[1], push[2], push[3], bias, half_offset]);
            // A workgroup per 16 x (subgroups * rows) tile and group of output tiles.
            p.dispatch([
                size.0.div_ceil(16) * 32 * subgroups,
                size.1.div_ceil(subgroups * rows),
                tiles.div_ceil(group_tiles),
            ]);
            (output, pooled)
        }
        _ => {
            // Up to four groups of four output channels an invocation, a divisor of them all, for
            // the network's portable pixels side by side.
            let groups = out_channels / 4;
            let per_thread = 4 * [4, 2, 1].into_iter().find(|d| groups % d == 0).unwrap_or(1);
            let pixels = network.portable_pixels;
            p.specialize("OUT_PER_THREAD", per_thread)
                .specialize("PIXELS", pixels)
                .push(&[push[0], push[1], push[2], push[3], offset]);
            p.dispatch([size.0.div_ceil(pixels), size.1, out_channels / per_thread]);
            let half = (pool_levels >= 1).then(|| add_pool(g, output, &format!("{name}.pool")));
            let quarter = half
                .filter(|_| pool_levels >= 2)
                .map(|half| add_pool(g, half, &format!("{name}.pool_quarter")));
            (output, [half, quarter])
        }
    }
}

/// Half of `size`, rounded up: the size of the next level down.
fn half_size((width, height): (u32, u32)) -> (u32, u32) {
    (width.div_ceil(2), height.div_ceil(2))
}

/// Adds 2x2 average pooling of `input` down to half its size, as the pass `name`.
fn add_pool(g: &mut RenderGraph, input: Tensor, name: &str) -> Tensor {
    let size = half_size(input.size);
    let mut p = g.compute_pass(name, &POOL);
    p.read("b_in", input.buffer)
        .specialize("CHANNELS", input.channels)
        .push(&[size.0, size.1, input.size.0, input.size.1]);
    let bytes = tensor_bytes(input.channels, size);
    let buffer = p.create_buffer("b_out", "neural.pooled", bytes);
    p.dispatch([size.0, size.1, input.channels / 4]);
    Tensor {
        buffer,
        channels: input.channels,
        size,
    }
}
