//! The learned temporal denoiser: a recurrent U-Net autoencoder (after Chaitanya et al. 2017)
//! trained on Lucid's own frames (`training/`), run in Vulkan compute (`shaders/neural/`).
//!
//! Per frame:
//! 1. **Record** ([`add_record`]): the light transport's surface images and the G-buffer are
//!    gathered into one planar float buffer (`shaders/neural/record.glsl`), which is also what
//!    `lucid dataset` writes for training.
//! 2. **Features**: log radiance, albedo, normal, roughness, log depth, and last frame's output
//!    reprojected by the motion vectors where depth and normal say the surface is the same, with
//!    the reprojection mask: 16 half-precision channels.
//! 3. **Network**: 3x3 convolutions at full, half and quarter resolution with skip connections
//!    ([`LAYERS`]), fused bias and ReLU, average pooling down and nearest upsampling up (read in
//!    place by the next convolution).
//! 4. **Output**: the network's log radiance blended with the reprojected history by a learned
//!    per-pixel weight (only where the mask allows), kept as the next frame's history, and
//!    re-modulated by albedo plus emission.
//!
//! The history (last output and surface) is the render graph's keyed temporal images under a
//! per-denoiser prefix, so two denoisers in one graph keep their own; a resize or
//! [`Executor::reset_history`](lucid_engine::graph::Executor::reset_history) starts afresh.
//! `training/model.py` is the reference of every step; `tests/neural_parity.rs` checks this
//! implementation against it.

mod weights;

pub use weights::{Layer, NetworkWeights, WeightsError, BUILTIN, FEATURES, FORMAT, LAYERS};

use crate::denoise::gbuffer::GBuffer;
use crate::denoise::{DenoiseInputs, Denoised, FrameDenoiser, FrameInfo, TransportRequest};
use crate::light_transport::SurfaceImages;
use crate::shaders::neural::{CONV, FEATURES as FEATURES_SHADER, OUTPUT, POOL, RECORD};
use lucid_engine::capture::ImageData;
use lucid_engine::graph::{Access, BufferHandle, ImageHandle, RenderGraph};
use lucid_engine::memory::{Buffer, ImageDesc};
use lucid_engine::{Context, EngineError, Result};
use std::sync::Arc;

/// Channels of a pixel's record (`RECORD_SIZE` in `shaders/neural/record.glsl`).
pub const RECORD_CHANNELS: u32 = 17;

/// The first channel of the first hit's albedo in a record (`RECORD_ALBEDO` in the shader).
pub const RECORD_ALBEDO: u32 = 3;
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
    let value = |c: usize, i: usize| {
        let at = (c * plane + i) * 4;
        f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]])
    };
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

/// Bytes of the record buffer of a `width` x `height` frame.
pub fn record_bytes(width: u32, height: u32) -> u64 {
    u64::from(RECORD_CHANNELS) * u64::from(width) * u64::from(height) * 4
}

/// The network's weights on the GPU, shared by every frame.
#[derive(Clone)]
pub struct Network {
    buffer: Arc<Buffer>,
    offsets: [u32; LAYERS.len()],
}

impl Network {
    /// Uploads `weights`.
    pub fn new(ctx: &Context, weights: &NetworkWeights) -> Result<Self> {
        let buffer = Buffer::with_data(
            ctx,
            "neural.weights",
            "denoiser",
            ash::vk::BufferUsageFlags::STORAGE_BUFFER,
            bytemuck::cast_slice(weights.packed()),
        )?;
        Ok(Self {
            buffer: Arc::new(buffer),
            offsets: std::array::from_fn(|i| weights.offset(i)),
        })
    }
}

/// The learned denoiser as the renderer's denoiser: the network and its history prefix. It runs
/// every frame on the frame's own radiance, and starts afresh when the scene changes (its history
/// describes the old scene).
#[derive(Clone)]
pub struct NeuralDenoiser {
    network: Network,
    prefix: String,
}

impl NeuralDenoiser {
    /// The denoiser running `network`, its history under `prefix`.
    pub fn new(network: Network, prefix: &str) -> Self {
        Self {
            network,
            prefix: prefix.to_owned(),
        }
    }
}

impl FrameDenoiser for NeuralDenoiser {
    fn plan(&mut self, _frame: &FrameInfo) -> Option<TransportRequest> {
        Some(TransportRequest::default())
    }

    fn add(&mut self, g: &mut RenderGraph, inputs: &DenoiseInputs) -> Denoised {
        let size = (inputs.width, inputs.height);
        let record = add_record(g, &inputs.surface, &inputs.gbuffer, size);
        Denoised {
            image: add_neural(g, &self.network, record, size, &self.prefix),
            gradient: None,
            record: Some(record),
        }
    }

    fn reset_on_scene_change(&self) -> Vec<String> {
        let (output, surface) = history_keys(&self.prefix);
        vec![output, surface]
    }
}

/// Adds the pass gathering a frame's record from the light transport's `surface` images and the
/// G-buffer; returns the record buffer (see [`record_bytes`]).
pub fn add_record(
    g: &mut RenderGraph,
    surface: &SurfaceImages,
    gbuffer: &GBuffer,
    (width, height): (u32, u32),
) -> BufferHandle {
    let mut p = g.add_pass("neural.record");
    let demodulated = p.read(surface.demodulated, Access::ComputeRead);
    let albedo = p.read(surface.albedo, Access::ComputeRead);
    let emission = p.read(surface.emission, Access::ComputeRead);
    let normal = p.read(gbuffer.normal_roughness, Access::ComputeRead);
    let depth = p.read(gbuffer.depth, Access::ComputeRead);
    let motion = p.read(gbuffer.motion, Access::ComputeRead);
    let record = p.create_buffer("neural.record", record_bytes(width, height));
    let record = p.write(record, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&RECORD)
            .image("u_demodulated", demodulated)
            .image("u_albedo", albedo)
            .image("u_emission", emission)
            .image("u_normal_roughness", normal)
            .image("u_depth", depth)
            .image("u_motion", motion)
            .buffer("b_record", record)
            .dispatch_threads([width, height, 1])
    });
    record
}

/// The history keys of a denoiser instance named `prefix`.
fn history_keys(prefix: &str) -> (String, String) {
    (format!("{prefix}.output"), format!("{prefix}.surface"))
}

/// A half-precision activation tensor of the network.
#[derive(Clone, Copy)]
struct Tensor {
    buffer: BufferHandle,
    channels: u32,
    size: (u32, u32),
}

/// Adds the denoiser over the frame `record` (from [`add_record`], or uploaded by a test) at
/// `width` x `height`, with its history under the keys `<prefix>.output` and `<prefix>.surface`;
/// returns the denoised radiance (`rgba32f`).
pub fn add_neural(
    g: &mut RenderGraph,
    network: &Network,
    record: BufferHandle,
    (width, height): (u32, u32),
    prefix: &str,
) -> ImageHandle {
    let weights = g.import_buffer("neural.weights", network.buffer.clone());
    let (output_key, surface_key) = history_keys(prefix);
    let output_history = g.temporal_image(&output_key, ImageDesc::rgba16f(width, height));
    let surface_history = g.temporal_image(&surface_key, ImageDesc::rgba32f(width, height));
    let full = (width, height);
    let half = (width.div_ceil(2), height.div_ceil(2));
    let quarter = (half.0.div_ceil(2), half.1.div_ceil(2));

    let mut p = g.add_pass(&format!("{prefix}.features"));
    let record_in = p.read(record, Access::ComputeRead);
    let prev_output = p.read(output_history.prev, Access::ComputeRead);
    let prev_surface = p.read(surface_history.prev, Access::ComputeRead);
    let surface = p.write(surface_history.cur, Access::ComputeWrite);
    let features = create_tensor(&mut p, "neural.features", FEATURES, full);
    p.execute(move |ctx| {
        let valid = u32::from(ctx.history_valid(prev_output) && ctx.history_valid(prev_surface));
        ctx.compute(&FEATURES_SHADER)
            .buffer("b_record", record_in)
            .image("u_prev_output", prev_output)
            .image("u_prev_surface", prev_surface)
            .image("u_surface", surface)
            .buffer("b_features", features.buffer)
            .push(&[width, height, valid])
            .dispatch_threads([width, height, 1])
    });
    let conv = |g: &mut RenderGraph, layer: usize, in0: Tensor, in1: Option<Tensor>, size| {
        add_conv(
            g,
            (weights, network.offsets[layer]),
            &LAYERS[layer],
            in0,
            in1,
            size,
        )
    };
    let e0 = conv(g, 0, features, None, full);
    let p0 = add_pool(g, e0, half);
    let e1 = conv(g, 1, p0, None, half);
    let p1 = add_pool(g, e1, quarter);
    let e2 = conv(g, 2, p1, None, quarter);
    let bottleneck = conv(g, 3, e2, None, quarter);
    let d1 = conv(g, 4, bottleneck, Some(e1), half);
    let d0 = conv(g, 5, d1, Some(e0), full);
    let net = conv(g, 6, d0, None, full);

    let mut p = g.add_pass(&format!("{prefix}.output"));
    let record_in = p.read(record, Access::ComputeRead);
    let features_in = p.read(features.buffer, Access::ComputeRead);
    let net_in = p.read(net.buffer, Access::ComputeRead);
    let history = p.write(output_history.cur, Access::ComputeWrite);
    let radiance = p.create_image(
        &format!("{prefix}.radiance"),
        ImageDesc::rgba32f(width, height),
    );
    let radiance = p.write(radiance, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&OUTPUT)
            .buffer("b_record", record_in)
            .buffer("b_features", features_in)
            .buffer("b_net", net_in)
            .image("u_output", history)
            .image("u_radiance", radiance)
            .push(&[width, height])
            .dispatch_threads([width, height, 1])
    });
    radiance
}

/// Creates and declares written a tensor of `channels` at `size` in pass `p`.
fn create_tensor(
    p: &mut lucid_engine::graph::PassBuilder<'_>,
    name: &str,
    channels: u32,
    size: (u32, u32),
) -> Tensor {
    let bytes = u64::from(channels) * u64::from(size.0) * u64::from(size.1) * 2;
    let buffer = p.create_buffer(name, bytes);
    Tensor {
        buffer: p.write(buffer, Access::ComputeWrite),
        channels,
        size,
    }
}

/// Adds one convolution layer at `size`: `in0` (upsampled when smaller than `size`), then `in1`.
fn add_conv(
    g: &mut RenderGraph,
    (weights, offset): (BufferHandle, u32),
    layer: &Layer,
    in0: Tensor,
    in1: Option<Tensor>,
    size: (u32, u32),
) -> Tensor {
    debug_assert_eq!(in0.channels, layer.in0);
    debug_assert_eq!(in1.map_or(0, |t| t.channels), layer.in1);
    let mut p = g.add_pass(&format!("neural.{}", layer.name));
    let weights = p.read(weights, Access::ComputeRead);
    let a = p.read(in0.buffer, Access::ComputeRead);
    // Without a second input the first is bound in its place (the shader does not read it).
    let b = match in1 {
        Some(t) => p.read(t.buffer, Access::ComputeRead),
        None => a,
    };
    let out = create_tensor(&mut p, &format!("neural.{}", layer.name), layer.out, size);
    let (layer, upsampled) = (*layer, in0.size != size);
    let per_thread = layer.out.min(16);
    p.execute(move |ctx| {
        ctx.compute(&CONV)
            .specialize("IN0_CHANNELS", layer.in0)
            .specialize("IN1_CHANNELS", layer.in1)
            .specialize("OUT_CHANNELS", layer.out)
            .specialize("OUT_PER_THREAD", per_thread)
            .specialize("IN0_UPSAMPLED", upsampled)
            .specialize("RELU", layer.name != "out")
            .buffer("b_in0", a)
            .buffer("b_in1", b)
            .buffer("b_weights", weights)
            .buffer("b_out", out.buffer)
            .push(&[size.0, size.1, in0.size.0, in0.size.1, offset])
            .dispatch_threads([size.0, size.1, layer.out / per_thread])
    });
    out
}

/// Adds 2x2 average pooling of `input` down to `size`.
fn add_pool(g: &mut RenderGraph, input: Tensor, size: (u32, u32)) -> Tensor {
    let mut p = g.add_pass("neural.pool");
    let a = p.read(input.buffer, Access::ComputeRead);
    let out = create_tensor(&mut p, "neural.pooled", input.channels, size);
    p.execute(move |ctx| {
        ctx.compute(&POOL)
            .specialize("CHANNELS", input.channels)
            .buffer("b_in", a)
            .buffer("b_out", out.buffer)
            .push(&[size.0, size.1, input.size.0, input.size.1])
            .dispatch_threads([size.0, size.1, input.channels / 4])
    });
    out
}
