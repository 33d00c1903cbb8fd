//! The network's weights on the GPU and the way its convolutions run there.

use super::weights::{Decoder, Layer, NetworkWeights};
use lucid_engine::context::DeviceKind;
use lucid_engine::memory::Buffer;
use lucid_engine::{Context, EngineError, Result};
use std::sync::Arc;

/// How the network's convolutions run.
///
/// ```
/// use lucid_passes::denoise::neural::InferencePath;
/// assert_eq!(InferencePath::ALL.map(InferencePath::short_name), ["portable", "tensor-cores"]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InferencePath {
    /// Plain compute shaders (`shaders/neural/conv.comp`): single-precision arithmetic on
    /// half-precision tensors, on every device, lavapipe included.
    Portable,
    /// Implicit GEMM on NVIDIA cooperative matrices (`shaders/neural/conv_coop.comp`): half-precision
    /// products summed in single precision on the tensor cores.
    TensorCores,
}

impl InferencePath {
    /// Every path, in the order the command line lists them.
    pub const ALL: [InferencePath; 2] = [InferencePath::Portable, InferencePath::TensorCores];

    /// The name used on the command line and in benchmark output.
    pub fn short_name(self) -> &'static str {
        match self {
            InferencePath::Portable => "portable",
            InferencePath::TensorCores => "tensor-cores",
        }
    }

    /// The fastest path `ctx`'s device runs.
    pub fn best(ctx: &Context) -> Self {
        if ctx.info().tensor_cores {
            InferencePath::TensorCores
        } else {
            InferencePath::Portable
        }
    }

    /// Every path `ctx`'s device runs.
    pub fn available(ctx: &Context) -> Vec<Self> {
        Self::ALL
            .into_iter()
            .filter(|path| path.check(ctx).is_ok())
            .collect()
    }

    /// An error naming the device when it cannot run this path.
    pub fn check(self, ctx: &Context) -> Result<()> {
        match self {
            InferencePath::TensorCores if !ctx.info().tensor_cores => {
                Err(EngineError::InvalidArgument(format!(
                    "the learned denoiser's tensor-core path needs VK_NV_cooperative_matrix with \
                     fp16 16x16x16 products, shaderFloat16, vulkanMemoryModel with device scope and 32-wide \
                     subgroups; {} lacks one of them (use the portable path)",
                    ctx.info().name
                )))
            }
            _ => Ok(()),
        }
    }
}

/// The network's weights on the GPU, shared by every frame, and the path its convolutions take.
#[derive(Clone)]
pub struct Network {
    pub(super) decoder: Decoder,
    /// [`NetworkWeights::scales`].
    pub(super) scales: u32,
    /// [`NetworkWeights::linear_mix`].
    pub(super) linear_mix: bool,
    /// [`NetworkWeights::emission_motion`].
    pub(super) emission_motion: f32,
    /// [`NetworkWeights::history_frames`].
    pub(super) history_frames: u32,
    /// [`NetworkWeights::spatial_variance_frames`].
    pub(super) spatial_variance_frames: u32,
    /// [`NetworkWeights::atrous_steps`].
    pub(super) atrous_steps: Vec<u32>,
    /// The layers, in execution order ([`Decoder::layers`]).
    pub(super) layers: Vec<Layer>,
    /// Every layer's float32 weights and bias (`conv.comp`'s layout).
    pub(super) buffer: Arc<Buffer>,
    /// Where each layer starts in `buffer`, in vec4s.
    pub(super) offsets: Vec<u32>,
    /// On the tensor-core path, the half-precision weights in `conv_coop.comp`'s layout and where
    /// each layer starts in them, in uvec4s.
    pub(super) half: Option<(Arc<Buffer>, Vec<u32>)>,
    pub(super) path: InferencePath,
    /// Pixels side by side that one invocation of the portable convolution computes
    /// ([`portable_conv_pixels`]).
    pub(super) portable_pixels: u32,
}

/// The most pixels an invocation of the portable convolution computes
/// ([`Network::with_portable_pixels`]).
const MAX_PORTABLE_PIXELS: u32 = 8;

/// Pixels side by side that one invocation of the portable convolution (`conv.comp`) computes on a
/// device of `kind`, every weight it loads serving each: eight on a CPU (on lavapipe the
/// convolutions of a 256x256 frame take 186 ms against 732 with one), two on a GPU, whose
/// registers hold the sums of each (on an H200 at 1080p, 10.14 ms against 11.32 with one and 11.77
/// with four).
fn portable_conv_pixels(kind: DeviceKind) -> u32 {
    if kind == DeviceKind::Cpu {
        MAX_PORTABLE_PIXELS
    } else {
        2
    }
}

impl Network {
    /// Uploads `weights`, to run on the fastest path the device has ([`InferencePath::best`]).
    pub fn new(ctx: &Context, weights: &NetworkWeights) -> Result<Self> {
        Self::with_path(ctx, weights, InferencePath::best(ctx))
    }

    /// Uploads `weights`, to run on `path`; an error when the device cannot run it.
    pub fn with_path(ctx: &Context, weights: &NetworkWeights, path: InferencePath) -> Result<Self> {
        path.check(ctx)?;
        let upload = |name: &str, bytes: &[u8]| {
            let usage = ash::vk::BufferUsageFlags::STORAGE_BUFFER;
            Buffer::with_data(ctx, name, "denoiser", usage, bytes).map(Arc::new)
        };
        let buffer = upload("neural.weights", bytemuck::cast_slice(weights.packed()))?;
        let half = match path {
            InferencePath::Portable => None,
            InferencePath::TensorCores => {
                let (halves, offsets) = pack_half_weights(weights);
                Some((
                    upload("neural.half_weights", bytemuck::cast_slice(&halves))?,
                    offsets,
                ))
            }
        };
        Ok(Self {
            decoder: weights.decoder(),
            scales: weights.scales(),
            linear_mix: weights.linear_mix(),
            emission_motion: weights.emission_motion(),
            history_frames: weights.history_frames(),
            spatial_variance_frames: weights.spatial_variance_frames(),
            atrous_steps: weights.atrous_steps().to_vec(),
            layers: weights.layers().to_vec(),
            buffer,
            offsets: (0..weights.layers().len())
                .map(|i| weights.offset(i))
                .collect(),
            half,
            path,
            portable_pixels: portable_conv_pixels(ctx.info().kind),
        })
    }

    /// The same network with its portable convolutions computing `pixels` pixels side by side an
    /// invocation (1 to 8) instead of the device's default: to compare them, which must agree.
    pub fn with_portable_pixels(mut self, pixels: u32) -> Result<Self> {
        if !(1..=MAX_PORTABLE_PIXELS).contains(&pixels) {
            return Err(EngineError::InvalidArgument(format!(
                "{pixels} pixels an invocation of the portable convolution, not 1 to \
                 {MAX_PORTABLE_PIXELS}"
            )));
        }
        self.portable_pixels = pixels;
        Ok(self)
    }

    /// The path the convolutions take.
    pub fn path(&self) -> InferencePath {
        self.path
    }

    /// What the network's last layers predict.
    pub fn decoder(&self) -> Decoder {
        self.decoder
    }
}

/// Input channels per chunk of `conv_coop.comp` (the matrices' K) and output channels per tile
/// (their N).
const MATRIX_SIZE: usize = 16;

/// The weights in `conv_coop.comp`'s layout: per layer, per chunk of 16 input channels and per tap,
/// a row-major (16 input x output channels rounded up to 16) half-precision matrix, zero past the
/// layer's channels. Returns the halves and where each layer starts, in uvec4s (eight halves).
fn pack_half_weights(weights: &NetworkWeights) -> (Vec<u16>, Vec<u32>) {
    let mut halves = Vec::new();
    let mut offsets = Vec::new();
    for (index, layer) in weights.layers().iter().enumerate() {
        offsets.push((halves.len() / 8) as u32);
        let (cin, cout) = (layer.inputs() as usize, layer.out_padded() as usize);
        let padded = cout.div_ceil(MATRIX_SIZE) * MATRIX_SIZE;
        // conv.comp's layout: output channels (padded to 4) innermost, at (tap * cin + ci) * cout.
        let packed = &weights.packed()[weights.offset(index) as usize * 4..];
        for chunk in 0..cin.div_ceil(MATRIX_SIZE) {
            for tap in 0..9 {
                for k in 0..MATRIX_SIZE {
                    let ci = chunk * MATRIX_SIZE + k;
                    halves.extend((0..padded).map(|co| {
                        let w = if ci < cin && co < cout {
                            packed[(tap * cin + ci) * cout + co]
                        } else {
                            0.0
                        };
                        half::f16::from_f32(w).to_bits()
                    }));
                }
            }
        }
    }
    (halves, offsets)
}
