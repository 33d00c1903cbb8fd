//! The network's weights on the GPU and the way its convolutions run there.

use super::weights::{Decoder, Layer, NetworkWeights};
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
    /// [`NetworkWeights::emission_motion`].
    pub(super) emission_motion: f32,
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
            emission_motion: weights.emission_motion(),
            layers: weights.layers().to_vec(),
            buffer,
            offsets: (0..weights.layers().len())
                .map(|i| weights.offset(i))
                .collect(),
            half,
            path,
        })
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
/// layer's channels; a layer whose first input is upsampled ([`Layer::upsamples_first_input`]) has,
/// in each of that input's chunks, the 16 matrices of [`folded_taps`] after the nine taps. Returns
/// the halves and where each layer starts, in uvec4s (eight halves).
fn pack_half_weights(weights: &NetworkWeights) -> (Vec<u16>, Vec<u32>) {
    let mut halves = Vec::new();
    let mut offsets = Vec::new();
    for (index, layer) in weights.layers().iter().enumerate() {
        offsets.push((halves.len() / 8) as u32);
        let (cin, cout) = (layer.inputs() as usize, layer.out_padded() as usize);
        let padded = cout.div_ceil(MATRIX_SIZE) * MATRIX_SIZE;
        // conv.comp's layout: output channels (padded to 4) innermost, at (tap * cin + ci) * cout.
        let packed = &weights.packed()[weights.offset(index) as usize * 4..];
        let weight = |tap: usize, ci: usize, co: usize| {
            if ci < cin && co < cout {
                packed[(tap * cin + ci) * cout + co]
            } else {
                0.0
            }
        };
        let folded_chunks = if layer.upsamples_first_input() {
            assert_eq!(layer.in0 as usize % MATRIX_SIZE, 0, "{}: in0", layer.name);
            layer.in0 as usize / MATRIX_SIZE
        } else {
            0
        };
        for chunk in 0..cin.div_ceil(MATRIX_SIZE) {
            let mut matrix = |w: &dyn Fn(usize, usize) -> f32| {
                for k in 0..MATRIX_SIZE {
                    let ci = chunk * MATRIX_SIZE + k;
                    halves.extend((0..padded).map(|co| half::f16::from_f32(w(ci, co)).to_bits()));
                }
            };
            for tap in 0..9 {
                matrix(&|ci, co| weight(tap, ci, co));
            }
            if chunk < folded_chunks {
                for folded in 0..16 {
                    matrix(&|ci, co| folded_taps(|tap| weight(tap, ci, co))[folded]);
                }
            }
        }
    }
    (halves, offsets)
}

/// A 3x3 convolution's weights `w` (by tap, `3 * dy + dx`) folded for an input upsampled 2x by
/// nearest neighbour: for the output pixels whose x and y have parities `(px, py)`, the convolution
/// is a 2x2 one of the input before upsampling, at offsets `parity + t - 1` (`t` 0 or 1) in each
/// direction from the pixel's own source, with each 2x2 tap's weight the sum of the 3x3 taps that
/// read that source pixel. Index `(2 * py + px) * 4 + 2 * ty + tx` (`conv_coop.comp`'s order).
fn folded_taps(w: impl Fn(usize) -> f32) -> [f32; 16] {
    // The 3x3 offsets (0..3) that land on the 2x2 tap `t` for parity `parity`.
    let sources = |parity: usize, t: usize| match (parity, t) {
        (0, 0) => 0..1,
        (0, _) => 1..3,
        (_, 0) => 0..2,
        _ => 2..3,
    };
    std::array::from_fn(|i| {
        let (class, tap) = (i / 4, i % 4);
        let (py, px, ty, tx) = (class / 2, class % 2, tap / 2, tap % 2);
        sources(py, ty)
            .flat_map(|dy| sources(px, tx).map(move |dx| 3 * dy + dx))
            .map(&w)
            .sum()
    })
}

#[cfg(test)]
mod tests {
    use super::folded_taps;

    /// A 3x3 convolution (zero padding) of `image` (`w` x `h`) upsampled 2x by nearest neighbour
    /// (cropped to `(w2, h2)`), at `(x, y)`.
    fn conv_upsampled(
        image: &[f32],
        (w, h): (usize, usize),
        (w2, h2): (usize, usize),
        k: &[f32; 9],
        (x, y): (usize, usize),
    ) -> f32 {
        let mut sum = 0.0;
        for dy in 0..3 {
            for dx in 0..3 {
                let (qx, qy) = (x as i64 + dx as i64 - 1, y as i64 + dy as i64 - 1);
                if qx < 0 || qy < 0 || qx >= w2 as i64 || qy >= h2 as i64 {
                    continue;
                }
                let (sx, sy) = ((qx as usize / 2).min(w - 1), (qy as usize / 2).min(h - 1));
                sum += k[3 * dy + dx] * image[sy * w + sx];
            }
        }
        sum
    }

    /// The folded 2x2 convolution of `image` before upsampling at `(x, y)` (zero outside it).
    fn conv_folded(
        image: &[f32],
        (w, h): (usize, usize),
        folded: &[f32; 16],
        (x, y): (usize, usize),
    ) -> f32 {
        let (px, py) = (x % 2, y % 2);
        let mut sum = 0.0;
        for t in 0..4 {
            let (ty, tx) = (t / 2, t % 2);
            let sx = (x / 2) as i64 + (px + tx) as i64 - 1;
            let sy = (y / 2) as i64 + (py + ty) as i64 - 1;
            if sx < 0 || sy < 0 || sx >= w as i64 || sy >= h as i64 {
                continue;
            }
            sum += folded[(2 * py + px) * 4 + t] * image[sy as usize * w + sx as usize];
        }
        sum
    }

    #[test]
    fn folded_weights_convolve_an_upsampled_image_exactly_but_at_odd_last_rows_and_columns() {
        let k: [f32; 9] = std::array::from_fn(|i| 0.37 * i as f32 - 1.1 + (i * i) as f32 * 0.05);
        let folded = folded_taps(|tap| k[tap]);
        for (w2, h2) in [(12_usize, 8_usize), (11, 7)] {
            let (w, h) = (w2.div_ceil(2), h2.div_ceil(2));
            let image: Vec<f32> = (0..w * h)
                .map(|i| ((i * 7919) % 23) as f32 / 7.0 - 1.0)
                .collect();
            let mut mismatched = Vec::new();
            for y in 0..h2 {
                for x in 0..w2 {
                    let expected = conv_upsampled(&image, (w, h), (w2, h2), &k, (x, y));
                    let got = conv_folded(&image, (w, h), &folded, (x, y));
                    if (expected - got).abs() > 1e-5 {
                        mismatched.push((x, y));
                    }
                }
            }
            // At odd sizes the pixel past the last column (row) lies in the image before
            // upsampling, so there the fold differs: conv_coop.comp runs those tiles unfolded.
            let odd_edge = |&(x, y): &(usize, usize)| {
                (w2 % 2 == 1 && x == w2 - 1) || (h2 % 2 == 1 && y == h2 - 1)
            };
            assert!(mismatched.iter().all(odd_edge), "{w2}x{h2}: {mismatched:?}");
            assert_eq!(
                mismatched.is_empty(),
                w2 % 2 == 0 && h2 % 2 == 0,
                "{w2}x{h2}"
            );
        }
    }
}
