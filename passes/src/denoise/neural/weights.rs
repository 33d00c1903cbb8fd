//! The learned denoiser's weights: a safetensors file of float32 `<layer>.weight` [out, in, 3, 3]
//! and `<layer>.bias` [out] tensors for each layer of its decoder's [`Decoder::layers`] (the
//! U-Net's [`Widths`] are the hidden layers' output channels), with
//! `format` metadata [`FORMAT`] and `decoder` metadata naming the [`Decoder`] (written by
//! `training/train.py`), packed into the order `shaders/neural/conv.comp` reads.

use safetensors::tensor::{Dtype, SafeTensors};
use std::path::Path;

/// The network format this code runs (`FORMAT` in `training/model.py`).
pub const FORMAT: &str = "lucid-rae-v3";

/// Channels of the network's input features (`FEATURES` in `training/model.py`; a multiple of 4,
/// `FEATURE_GROUPS` in `shaders/neural/tensor.glsl`).
pub const FEATURES: u32 = 24;

/// Taps of the kernel-predicting decoder's per-pixel 5x5 kernels (`TAPS` in
/// `training/kernel_model.py`).
pub const KERNEL_TAPS: u32 = 25;

/// One 3x3 convolution of the network.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layer {
    /// The tensor name prefix.
    pub name: &'static str,
    /// Channels of the first input.
    pub in0: u32,
    /// Channels of the second input, concatenated after the first (a skip connection; 0: none).
    pub in1: u32,
    /// Output channels.
    pub out: u32,
    /// Whether a ReLU follows (all but the output layers).
    pub relu: bool,
}

impl Layer {
    const fn hidden(name: &'static str, in0: u32, in1: u32, out: u32) -> Self {
        Self {
            name,
            in0,
            in1,
            out,
            relu: true,
        }
    }

    const fn output(name: &'static str, in0: u32, out: u32) -> Self {
        Self {
            name,
            in0,
            in1: 0,
            out,
            relu: false,
        }
    }

    /// Input channels in all.
    pub fn inputs(&self) -> u32 {
        self.in0 + self.in1
    }

    /// Output channels as the shaders store them: rounded up to a multiple of 4 (the padding is
    /// zero).
    pub fn out_padded(&self) -> u32 {
        self.out.next_multiple_of(4)
    }

    /// Floats this layer takes in the packed buffer (weights, then bias).
    fn packed_len(&self) -> usize {
        (9 * self.inputs() * self.out_padded() + self.out_padded()) as usize
    }
}

/// The U-Net's hidden layers, in execution order (`HIDDEN` in `training/model.py`).
pub const HIDDEN: [&str; 6] = ["enc0", "enc1", "enc2", "bottleneck", "dec1", "dec0"];

/// The U-Net's widths: the output channels of each of its [`HIDDEN`] layers, multiples of 16
/// from 16 to 256. A weights file's are its tensors' shapes; the committed network's are
/// [`Widths::COMMITTED`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Widths(pub [u32; 6]);

impl Widths {
    /// The committed network's (`WIDTHS` in `training/model.py`).
    pub const COMMITTED: Widths = Widths([16, 32, 64, 64, 32, 16]);

    /// The U-Net's layers up to the decoder's output layers, in execution order (`unet_layers` in
    /// `training/model.py` without `out`): each reads what the layers before it write.
    pub fn unet(self) -> [Layer; 6] {
        let [e0, e1, e2, b, d1, d0] = self.0;
        let [enc0, enc1, enc2, bottleneck, dec1, dec0] = HIDDEN;
        [
            Layer::hidden(enc0, FEATURES, 0, e0),
            Layer::hidden(enc1, e0, 0, e1),
            Layer::hidden(enc2, e1, 0, e2),
            Layer::hidden(bottleneck, e2, 0, b),
            Layer::hidden(dec1, b, e1, d1),
            Layer::hidden(dec0, d1, e0, d0),
        ]
    }
}

/// The kernel decoder's heads, finest first, one a scale (`HEAD_NAMES` in
/// `training/kernel_model.py`): full resolution and each coarser one half the previous.
pub const KERNEL_HEADS: [&str; 5] = [
    "out",
    "out_half",
    "out_quarter",
    "out_eighth",
    "out_sixteenth",
];

/// The committed network's kernel scales (`SCALES` in `training/kernel_model.py`).
pub const KERNEL_SCALES: u32 = 4;

/// The fewest kernel scales a file has (the committed weights' until the twentieth session).
const FEWEST_SCALES: u32 = 3;

/// Output channels of the kernel decoder's head `level` (0 the full resolution's) in a network of
/// `scales`: its kernel's 25 logits, the weight `a` of the next coarser scale (all but the
/// coarsest) and at full resolution the blend weight and, with `linear_mix`, the linear mix's
/// logit.
fn head_channels(level: u32, scales: u32, linear_mix: bool) -> u32 {
    let full = u32::from(level == 0);
    KERNEL_TAPS + u32::from(level + 1 < scales) + full + full * u32::from(linear_mix)
}

/// What the network's last layers predict (the weights file's `decoder` metadata; measured
/// against each other in `training/README.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decoder {
    /// Log radiance and a blend weight per pixel (`training/model.py`): one output layer.
    Direct,
    /// Per-pixel 5x5 kernels filtering the noisy radiance at full, half, quarter (and eighth)
    /// resolution, composited coarse to fine (`training/kernel_model.py`): one output layer a
    /// scale ([`KERNEL_HEADS`]).
    Kernel,
}

impl Decoder {
    /// The name in weights files.
    pub fn name(self) -> &'static str {
        match self {
            Decoder::Direct => "direct",
            Decoder::Kernel => "kernel",
        }
    }

    fn from_name(name: &str) -> Option<Self> {
        [Decoder::Direct, Decoder::Kernel]
            .into_iter()
            .find(|d| d.name() == name)
    }

    /// Every layer of a network of `widths` with this decoder (the kernel decoder's of `scales`,
    /// 3 to 5, with or without the [`NetworkWeights::linear_mix`]), in execution order:
    /// [`Widths::unet`], then the output layers on the last decoder features (the kernel decoder's
    /// finest first, [`KERNEL_HEADS`]).
    pub fn layers(self, widths: Widths, scales: u32, linear_mix: bool) -> Vec<Layer> {
        let features = widths.0[5];
        let outputs = match self {
            Decoder::Direct => vec![Layer::output("out", features, 4)],
            Decoder::Kernel => (0..scales)
                .map(|level| {
                    let name = KERNEL_HEADS[level as usize];
                    Layer::output(name, features, head_channels(level, scales, linear_mix))
                })
                .collect(),
        };
        widths.unet().into_iter().chain(outputs).collect()
    }
}

/// The weights of the committed network (`passes/src/denoise/neural/lucid-rae-v3.safetensors`; see
/// `training/README.md` for the command and data that produced them).
pub const BUILTIN: &[u8] = include_bytes!("lucid-rae-v3.safetensors");

/// A weights file that cannot be used, naming the file and, where it applies, the tensor.
#[derive(Debug, thiserror::Error)]
pub enum WeightsError {
    /// The file could not be read.
    #[error("denoiser weights {file} cannot be read")]
    Read {
        /// The file.
        file: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not a safetensors file (truncated, corrupt header, ...).
    #[error("denoiser weights {file}: not a valid safetensors file: {reason}")]
    Format {
        /// The file.
        file: String,
        /// What the parser said.
        reason: String,
    },
    /// The file is for another network.
    #[error("denoiser weights {file}: format {found:?}, expected {FORMAT:?}")]
    Network {
        /// The file.
        file: String,
        /// The `format` metadata found (empty when absent).
        found: String,
    },
    /// The file's decoder is none this code runs.
    #[error("denoiser weights {file}: decoder {found:?}, expected \"direct\" or \"kernel\"")]
    Decoder {
        /// The file.
        file: String,
        /// The `decoder` metadata found (empty when absent).
        found: String,
    },
    /// A metadata entry that sets a parameter holds no valid value.
    #[error("denoiser weights {file}: metadata {key} {found:?}: {expected}")]
    Metadata {
        /// The file.
        file: String,
        /// The metadata key.
        key: String,
        /// Its value.
        found: String,
        /// What it must be.
        expected: String,
    },
    /// A tensor is missing, of the wrong type or shape, or holds a non-finite value.
    #[error("denoiser weights {file}: tensor {tensor}: {problem}")]
    Tensor {
        /// The file.
        file: String,
        /// The tensor.
        tensor: String,
        /// What is wrong with it.
        problem: String,
    },
}

/// The least weight of this frame's emission, per pixel of motion, in its average over time that
/// re-modulates the output (`EMISSION_MOTION` in training/model.py, `antialias_surface`), where
/// the weights file's `emission_motion` metadata does not set it: none, since the average takes
/// only taps of the same object (measured in training/README.md).
pub const EMISSION_MOTION: f32 = 0.0;

/// The most frames the running means average before they become exponential moving averages
/// (`N_MAX` in training/model.py), where the weights file's `history_frames` metadata does not set
/// a smaller number; the network's input divides the history length by it either way.
pub const HISTORY_FRAMES: u32 = 32;

/// The history lengths below which the network's variance inputs are taken over each pixel's 3x3
/// neighbourhood of the frame's samples rather than over its history (`SPATIAL_VARIANCE_FRAMES`
/// in training/model.py, `features`), where the weights file's `spatial_variance_frames` metadata
/// does not set them: none, so a first frame's variance inputs are 0.
pub const SPATIAL_VARIANCE_FRAMES: u32 = 0;

/// The most a-trous steps of the gated filter over the output (the weights file's `atrous_steps`
/// metadata; training/model.py, `atrous`).
pub const ATROUS_MAX_STEPS: usize = 5;

/// The widest spacing of an a-trous step's taps, in pixels (the spacings are powers of two, which
/// the steps' tiles in shared memory need).
pub const ATROUS_MAX_SPACING: u32 = 64;

/// The a-trous steps' spacings from the metadata entry `atrous_steps` of `file` (its text
/// `found`, comma-separated): none where the entry is absent or empty, an error where it is not 1
/// to [`ATROUS_MAX_STEPS`] powers of two from 1 to [`ATROUS_MAX_SPACING`].
fn atrous_steps(file: &str, found: String) -> Result<Vec<u32>, WeightsError> {
    if found.trim().is_empty() {
        return Ok(Vec::new());
    }
    let steps: Option<Vec<u32>> = found
        .split(',')
        .map(|step| {
            step.trim()
                .parse::<u32>()
                .ok()
                .filter(|s| s.is_power_of_two() && *s <= ATROUS_MAX_SPACING)
        })
        .collect();
    steps
        .filter(|steps| steps.len() <= ATROUS_MAX_STEPS)
        .ok_or_else(|| WeightsError::Metadata {
            file: file.to_owned(),
            key: "atrous_steps".into(),
            found,
            expected: format!(
                "1 to {ATROUS_MAX_STEPS} comma-separated powers of two from 1 to \
                 {ATROUS_MAX_SPACING}"
            ),
        })
}

/// A number from the metadata entry `key` of `file` (its text `found`): `default` where the entry
/// is absent, an error saying what was `expected` where it does not parse or is not `valid`.
fn metadata_number<T: std::str::FromStr>(
    file: &str,
    key: &str,
    found: String,
    default: T,
    valid: impl Fn(&T) -> bool,
    expected: &str,
) -> Result<T, WeightsError> {
    if found.is_empty() {
        return Ok(default);
    }
    found
        .parse::<T>()
        .ok()
        .filter(valid)
        .ok_or_else(|| WeightsError::Metadata {
            file: file.to_owned(),
            key: key.into(),
            found,
            expected: expected.into(),
        })
}

/// Weights ready for upload: every layer's weights and bias, packed.
#[derive(Clone, Debug, PartialEq)]
pub struct NetworkWeights {
    decoder: Decoder,
    scales: u32,
    linear_mix: bool,
    emission_motion: f32,
    history_frames: u32,
    spatial_variance_frames: u32,
    atrous_steps: Vec<u32>,
    widths: Widths,
    layers: Vec<Layer>,
    packed: Vec<f32>,
    offsets: Vec<u32>,
}

impl NetworkWeights {
    /// Loads a weights file.
    pub fn load(path: &Path) -> Result<Self, WeightsError> {
        let file = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|source| WeightsError::Read {
            file: file.clone(),
            source,
        })?;
        Self::from_bytes(&bytes, &file)
    }

    /// The committed network's weights.
    pub fn builtin() -> Self {
        Self::from_bytes(BUILTIN, "builtin").expect("the committed weights load (tested)")
    }

    /// Parses the bytes of a weights file; `file` names it in errors.
    pub fn from_bytes(bytes: &[u8], file: &str) -> Result<Self, WeightsError> {
        let format_error = |reason: String| WeightsError::Format {
            file: file.to_owned(),
            reason,
        };
        let (_, metadata) =
            SafeTensors::read_metadata(bytes).map_err(|e| format_error(e.to_string()))?;
        let entry = |key: &str| {
            metadata
                .metadata()
                .as_ref()
                .and_then(|m| m.get(key).cloned())
                .unwrap_or_default()
        };
        let found = entry("format");
        if found != FORMAT {
            return Err(WeightsError::Network {
                file: file.to_owned(),
                found,
            });
        }
        let found = entry("decoder");
        let decoder = Decoder::from_name(&found).ok_or_else(|| WeightsError::Decoder {
            file: file.to_owned(),
            found,
        })?;
        let emission_motion = metadata_number(
            file,
            "emission_motion",
            entry("emission_motion"),
            EMISSION_MOTION,
            |v: &f32| v.is_finite() && *v >= 0.0,
            "a finite number from 0 up",
        )?;
        let history_frames = metadata_number(
            file,
            "history_frames",
            entry("history_frames"),
            HISTORY_FRAMES,
            |v| (1..=HISTORY_FRAMES).contains(v),
            &format!("a whole number from 1 to {HISTORY_FRAMES}"),
        )?;
        let spatial_variance_frames = metadata_number(
            file,
            "spatial_variance_frames",
            entry("spatial_variance_frames"),
            SPATIAL_VARIANCE_FRAMES,
            |v| *v <= HISTORY_FRAMES,
            &format!("a whole number from 0 to {HISTORY_FRAMES}"),
        )?;
        let atrous_steps = atrous_steps(file, entry("atrous_steps"))?;
        let gate = !atrous_steps.is_empty();
        let tensors = SafeTensors::deserialize(bytes).map_err(|e| format_error(e.to_string()))?;
        let widths = read_widths(&tensors, file)?;
        let (scales, linear_mix) = match decoder {
            Decoder::Direct => (KERNEL_SCALES, false),
            Decoder::Kernel => {
                let scales = read_scales(&tensors);
                (scales, read_linear_mix(&tensors, scales, gate))
            }
        };
        let mut layers = decoder.layers(widths, scales, linear_mix);
        if gate {
            add_gate_channel(&mut layers);
        }
        let mut packed = Vec::with_capacity(layers.iter().map(Layer::packed_len).sum());
        let mut offsets = Vec::with_capacity(layers.len());
        for layer in &layers {
            offsets.push((packed.len() / 4) as u32);
            let (cin, cout) = (layer.inputs() as usize, layer.out as usize);
            let padding = (layer.out_padded() - layer.out) as usize;
            let weight = read_tensor(
                &tensors,
                file,
                &format!("{}.weight", layer.name),
                &[cout, cin, 3, 3],
            )?;
            let bias = read_tensor(&tensors, file, &format!("{}.bias", layer.name), &[cout])?;
            // conv.comp reads vec4s of four consecutive output channels at
            // (tap * cin + ci) * cout / 4, the output channels padded with zeros to a multiple of 4.
            for tap in 0..9 {
                for ci in 0..cin {
                    packed.extend((0..cout).map(|co| weight[(co * cin + ci) * 9 + tap]));
                    packed.extend(std::iter::repeat_n(0.0, padding));
                }
            }
            packed.extend_from_slice(&bias);
            packed.extend(std::iter::repeat_n(0.0, padding));
        }
        Ok(Self {
            decoder,
            scales,
            linear_mix,
            emission_motion,
            history_frames,
            spatial_variance_frames,
            atrous_steps,
            widths,
            layers,
            packed,
            offsets,
        })
    }

    /// The decoder these weights are for.
    pub fn decoder(&self) -> Decoder {
        self.decoder
    }

    /// The kernel decoder's scales, 3 to 5 (for the direct decoder [`KERNEL_SCALES`], unused).
    pub fn scales(&self) -> u32 {
        self.scales
    }

    /// Whether the kernel decoder mixes its log-space and linear-space results per pixel by a last
    /// channel of its full-resolution head (`training/kernel_model.py`, `linear_mix`).
    pub fn linear_mix(&self) -> bool {
        self.linear_mix
    }

    /// The least weight of this frame's emission per pixel of motion in its average over time
    /// (the file's `emission_motion` metadata, else [`EMISSION_MOTION`]).
    pub fn emission_motion(&self) -> f32 {
        self.emission_motion
    }

    /// The most frames the running means average before they become exponential moving averages
    /// (the file's `history_frames` metadata, else [`HISTORY_FRAMES`]).
    pub fn history_frames(&self) -> u32 {
        self.history_frames
    }

    /// The history lengths below which the variance inputs are spatial (the file's
    /// `spatial_variance_frames` metadata, else [`SPATIAL_VARIANCE_FRAMES`]).
    pub fn spatial_variance_frames(&self) -> u32 {
        self.spatial_variance_frames
    }

    /// The spacings of the a-trous steps that filter the output's illumination further, blended in
    /// by a gate per pixel, the output layer's last channel (the file's `atrous_steps` metadata;
    /// none without it, and no gate channel).
    pub fn atrous_steps(&self) -> &[u32] {
        &self.atrous_steps
    }

    /// The U-Net's widths (its tensors' shapes).
    pub fn widths(&self) -> Widths {
        self.widths
    }

    /// The layers, in execution order ([`Decoder::layers`] of [`NetworkWeights::widths`] and
    /// [`NetworkWeights::scales`]).
    pub fn layers(&self) -> &[Layer] {
        &self.layers
    }

    /// The packed floats (vec4-aligned per layer), as `shaders/neural/conv.comp` reads them.
    pub fn packed(&self) -> &[f32] {
        &self.packed
    }

    /// The first vec4 of layer `index` of [`NetworkWeights::layers`] in [`NetworkWeights::packed`].
    pub fn offset(&self, index: usize) -> u32 {
        self.offsets[index]
    }
}

/// The U-Net's widths: each hidden layer's output channels, from its weights' shape (their other
/// dimensions are checked as they are read).
fn read_widths(tensors: &SafeTensors<'_>, file: &str) -> Result<Widths, WeightsError> {
    let mut widths = [0; 6];
    for (width, name) in widths.iter_mut().zip(HIDDEN) {
        let tensor = format!("{name}.weight");
        let problem = |problem: String| WeightsError::Tensor {
            file: file.to_owned(),
            tensor: tensor.clone(),
            problem,
        };
        let view = tensors
            .tensor(&tensor)
            .map_err(|_| problem("missing".into()))?;
        let out = view.shape().first().copied().unwrap_or(0);
        *width = u32::try_from(out)
            .ok()
            .filter(|&w| w > 0 && w % 16 == 0 && w <= 256)
            .ok_or_else(|| {
                problem(format!(
                    "{out} output channels, expected a multiple of 16 from 16 to 256"
                ))
            })?;
    }
    Ok(Widths(widths))
}

/// The kernel decoder's scales: three, and one more for each coarser head the file has in turn
/// (eighth, then sixteenth resolution; the heads' shapes are checked as they are read).
fn read_scales(tensors: &SafeTensors<'_>) -> u32 {
    let coarser = KERNEL_HEADS[FEWEST_SCALES as usize..]
        .iter()
        .take_while(|head| tensors.tensor(&format!("{head}.weight")).is_ok())
        .count();
    FEWEST_SCALES + coarser as u32
}

/// Whether the kernel decoder's full-resolution head has the linear mix's channel: one more output
/// channel than without, before the `gate`'s where it has one (any other count is refused with the
/// head's shape when it is read).
fn read_linear_mix(tensors: &SafeTensors<'_>, scales: u32, gate: bool) -> bool {
    let name = format!("{}.weight", KERNEL_HEADS[0]);
    tensors
        .tensor(&name)
        .ok()
        .and_then(|t| t.shape().first().copied())
        == Some((head_channels(0, scales, true) + u32::from(gate)) as usize)
}

/// Adds the gate of the a-trous filter to `layers`: one more output channel, the last, of the
/// layer `out` (the direct decoder's output layer, the kernel decoder's full-resolution head).
fn add_gate_channel(layers: &mut [Layer]) {
    let out = layers
        .iter_mut()
        .find(|layer| layer.name == KERNEL_HEADS[0])
        .expect("both decoders have an `out` layer");
    out.out += 1;
}

/// The float32 values of tensor `name`, which must have `shape` and be finite.
fn read_tensor(
    tensors: &SafeTensors<'_>,
    file: &str,
    name: &str,
    shape: &[usize],
) -> Result<Vec<f32>, WeightsError> {
    let problem = |problem: String| WeightsError::Tensor {
        file: file.to_owned(),
        tensor: name.to_owned(),
        problem,
    };
    let view = tensors
        .tensor(name)
        .map_err(|_| problem("missing".into()))?;
    if view.dtype() != Dtype::F32 {
        return Err(problem(format!("type {:?}, expected F32", view.dtype())));
    }
    if view.shape() != shape {
        return Err(problem(format!(
            "shape {:?}, expected {shape:?}",
            view.shape()
        )));
    }
    let values: Vec<f32> = bytemuck::pod_collect_to_vec(view.data());
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(problem(format!("value {i} is {}", values[i])));
    }
    Ok(values)
}

#[cfg(test)]
mod tests {
    use super::*;
    use safetensors::tensor::TensorView;
    use std::collections::HashMap;

    /// A weights file with `format` and `decoder`, every layer's tensors, `edit` applied to (name,
    /// shape, values).
    fn file_for(
        format: &str,
        decoder: Decoder,
        edit: impl Fn(&str, &mut Vec<usize>, &mut Vec<f32>) -> bool,
    ) -> Vec<u8> {
        file_with_metadata(format, decoder, Widths::COMMITTED, &[], edit)
    }

    /// A kernel decoder's weights file of `scales`, every tensor 0.5.
    fn file_of_scales(scales: u32) -> Vec<u8> {
        file_with_layers(
            FORMAT,
            Decoder::Kernel,
            &Decoder::Kernel.layers(Widths::COMMITTED, scales, false),
            &[],
            |_, _, _| true,
        )
    }

    /// [`file_for`] of a network of `widths` with more metadata entries.
    fn file_with_metadata(
        format: &str,
        decoder: Decoder,
        widths: Widths,
        extra: &[(&str, &str)],
        edit: impl Fn(&str, &mut Vec<usize>, &mut Vec<f32>) -> bool,
    ) -> Vec<u8> {
        let layers = decoder.layers(widths, KERNEL_SCALES, false);
        file_with_layers(format, decoder, &layers, extra, edit)
    }

    /// [`file_with_metadata`] with the tensors of `layers`.
    fn file_with_layers(
        format: &str,
        decoder: Decoder,
        layers: &[Layer],
        extra: &[(&str, &str)],
        edit: impl Fn(&str, &mut Vec<usize>, &mut Vec<f32>) -> bool,
    ) -> Vec<u8> {
        let mut tensors = Vec::new();
        for layer in layers {
            let (cin, cout) = (layer.inputs() as usize, layer.out as usize);
            for (kind, shape) in [("weight", vec![cout, cin, 3, 3]), ("bias", vec![cout])] {
                let name = format!("{}.{kind}", layer.name);
                let mut shape = shape;
                let mut values = vec![0.5f32; shape.iter().product()];
                if edit(&name, &mut shape, &mut values) {
                    tensors.push((name, shape, values));
                }
            }
        }
        let bytes: Vec<Vec<u8>> = tensors
            .iter()
            .map(|(_, _, v)| bytemuck::cast_slice(v).to_vec())
            .collect();
        let views: HashMap<String, TensorView<'_>> = tensors
            .iter()
            .zip(&bytes)
            .map(|((name, shape, _), b)| {
                let view = TensorView::new(Dtype::F32, shape.clone(), b).expect("view");
                (name.clone(), view)
            })
            .collect();
        let mut metadata = HashMap::from([
            ("format".to_string(), format.to_string()),
            ("decoder".to_string(), decoder.name().to_string()),
        ]);
        metadata.extend(extra.iter().map(|(k, v)| (k.to_string(), v.to_string())));
        safetensors::serialize(&views, &Some(metadata)).expect("serialize")
    }

    /// A direct decoder's weights file ([`file_for`]).
    fn file(format: &str, edit: impl Fn(&str, &mut Vec<usize>, &mut Vec<f32>) -> bool) -> Vec<u8> {
        file_for(format, Decoder::Direct, edit)
    }

    fn error(bytes: &[u8]) -> String {
        NetworkWeights::from_bytes(bytes, "w.safetensors")
            .expect_err("must be refused")
            .to_string()
    }

    #[test]
    fn committed_weights_load_and_pack_every_layer() {
        let weights = NetworkWeights::builtin();
        assert_eq!(weights.widths(), Widths::COMMITTED);
        let floats: usize = weights.layers().iter().map(Layer::packed_len).sum();
        assert_eq!(weights.packed().len(), floats);
        assert_eq!(weights.offset(0), 0);
        for decoder in [Decoder::Direct, Decoder::Kernel] {
            let good = file_for(FORMAT, decoder, |_, _, _| true);
            let loaded = NetworkWeights::from_bytes(&good, "w").expect("loads");
            assert_eq!(loaded.decoder(), decoder);
            let layers = decoder.layers(Widths::COMMITTED, KERNEL_SCALES, false);
            assert_eq!(loaded.layers(), layers);
        }
    }

    #[test]
    fn the_scales_come_from_the_heads() {
        assert_eq!(NetworkWeights::builtin().scales(), KERNEL_SCALES);
        for (scales, heads) in [
            (3, vec![("out", 27), ("out_half", 26), ("out_quarter", 25)]),
            (
                4,
                vec![
                    ("out", 27),
                    ("out_half", 26),
                    ("out_quarter", 26),
                    ("out_eighth", 25),
                ],
            ),
            (
                5,
                vec![
                    ("out", 27),
                    ("out_half", 26),
                    ("out_quarter", 26),
                    ("out_eighth", 26),
                    ("out_sixteenth", 25),
                ],
            ),
        ] {
            let weights = NetworkWeights::from_bytes(&file_of_scales(scales), "w").expect("loads");
            assert_eq!(weights.scales(), scales);
            let found: Vec<_> = weights.layers()[6..]
                .iter()
                .map(|l| (l.name, l.out))
                .collect();
            assert_eq!(found, heads, "{scales} scales");
        }
        // An eighth head that reads other channels than dec0 writes is refused, naming it.
        let bytes = file_with_layers(
            FORMAT,
            Decoder::Kernel,
            &Decoder::Kernel.layers(Widths::COMMITTED, 4, false),
            &[],
            |name, shape, values| {
                if name == "out_eighth.weight" {
                    shape[1] = 32;
                    values.resize(shape.iter().product(), 0.5);
                }
                true
            },
        );
        let message = error(&bytes);
        assert!(
            message.contains("out_eighth.weight") && message.contains("expected [25, 16, 3, 3]"),
            "{message}"
        );
    }

    #[test]
    fn the_linear_mix_comes_from_the_full_heads_channels() {
        assert!(!NetworkWeights::builtin().linear_mix());
        for scales in 3..=5 {
            let layers = Decoder::Kernel.layers(Widths::COMMITTED, scales, true);
            let bytes = file_with_layers(FORMAT, Decoder::Kernel, &layers, &[], |_, _, _| true);
            let weights = NetworkWeights::from_bytes(&bytes, "w").expect("loads");
            assert!(weights.linear_mix(), "{scales} scales");
            assert_eq!(weights.layers()[6].out, 28);
            assert_eq!(weights.layers()[6].out_padded(), 28);
        }
        // Two channels more is neither network: refused, naming the head.
        let bytes = file_with_layers(
            FORMAT,
            Decoder::Kernel,
            &Decoder::Kernel.layers(Widths::COMMITTED, 4, true),
            &[],
            |name, shape, values| {
                if name.starts_with("out.") {
                    shape[0] = 29;
                    values.resize(shape.iter().product(), 0.5);
                }
                true
            },
        );
        let message = error(&bytes);
        assert!(
            message.contains("out.weight") && message.contains("expected [27, 16, 3, 3]"),
            "{message}"
        );
    }

    /// Checks one metadata entry the renderer reads: `read` gives `default` without it and `value`
    /// with it set to `text`, and each of `bad` is refused with an error naming the file, the key
    /// and what it found.
    fn check_metadata_entry<T: PartialEq + std::fmt::Debug>(
        key: &str,
        read: impl Fn(&NetworkWeights) -> T,
        default: T,
        (text, value): (&str, T),
        bad: &[&str],
    ) {
        let plain = file_for(FORMAT, Decoder::Kernel, |_, _, _| true);
        let weights = NetworkWeights::from_bytes(&plain, "w").expect("loads");
        assert_eq!(read(&weights), default);
        let set = |text: &str| {
            file_with_metadata(
                FORMAT,
                Decoder::Kernel,
                Widths::COMMITTED,
                &[(key, text)],
                |_, _, _| true,
            )
        };
        let weights = NetworkWeights::from_bytes(&set(text), "w").expect("loads");
        assert_eq!(read(&weights), value);
        for bad in bad {
            let message = error(&set(bad));
            assert!(
                message.contains("w.safetensors")
                    && message.contains(&format!("metadata {key} \"{bad}\"")),
                "{message}"
            );
        }
    }

    #[test]
    fn the_emission_motion_comes_from_the_metadata_when_it_is_there() {
        check_metadata_entry(
            "emission_motion",
            NetworkWeights::emission_motion,
            EMISSION_MOTION,
            ("0.25", 0.25),
            &["-1", "NaN", "inf", "fast"],
        );
    }

    #[test]
    fn the_history_frames_come_from_the_metadata_when_it_is_there() {
        check_metadata_entry(
            "history_frames",
            NetworkWeights::history_frames,
            HISTORY_FRAMES,
            ("20", 20),
            &["0", "33", "-1", "20.5", "long"],
        );
    }

    #[test]
    fn the_spatial_variance_frames_come_from_the_metadata_when_it_is_there() {
        check_metadata_entry(
            "spatial_variance_frames",
            NetworkWeights::spatial_variance_frames,
            SPATIAL_VARIANCE_FRAMES,
            ("4", 4),
            &["33", "-1", "3.5", "few"],
        );
    }

    #[test]
    fn the_atrous_steps_come_from_the_metadata_with_the_gate_channel() {
        assert_eq!(NetworkWeights::builtin().atrous_steps(), [4, 8]);
        let gated = |decoder: Decoder, linear_mix: bool| {
            let mut layers = decoder.layers(Widths::COMMITTED, KERNEL_SCALES, linear_mix);
            add_gate_channel(&mut layers);
            layers
        };
        let steps = [("atrous_steps", "4, 8,16")];
        for (decoder, linear_mix, out) in [
            (Decoder::Kernel, false, 28),
            (Decoder::Kernel, true, 29),
            (Decoder::Direct, false, 5),
        ] {
            let layers = gated(decoder, linear_mix);
            let bytes = file_with_layers(FORMAT, decoder, &layers, &steps, |_, _, _| true);
            let weights = NetworkWeights::from_bytes(&bytes, "w").expect("loads");
            assert_eq!(weights.atrous_steps(), [4, 8, 16]);
            assert_eq!(weights.linear_mix(), linear_mix, "{decoder:?}");
            assert_eq!(weights.layers()[6].name, "out");
            assert_eq!(weights.layers()[6].out, out, "{decoder:?}");
        }
        // The steps without the gate's channel: refused, naming the head and the shape it needs.
        let layers = Decoder::Kernel.layers(Widths::COMMITTED, KERNEL_SCALES, false);
        let bytes = file_with_layers(FORMAT, Decoder::Kernel, &layers, &steps, |_, _, _| true);
        let message = error(&bytes);
        assert!(
            message.contains("out.weight") && message.contains("expected [28, 16, 3, 3]"),
            "{message}"
        );
        let layers = gated(Decoder::Kernel, false);
        for bad in ["0", "128", "12", "4,8,16,32,64,2", "4;8", "4,,8", "wide"] {
            let metadata = [("atrous_steps", bad)];
            let bytes =
                file_with_layers(FORMAT, Decoder::Kernel, &layers, &metadata, |_, _, _| true);
            let message = error(&bytes);
            assert!(
                message.contains("w.safetensors")
                    && message.contains(&format!("metadata atrous_steps \"{bad}\"")),
                "{message}"
            );
        }
    }

    #[test]
    fn the_widths_come_from_the_weights_shapes() {
        let slim = Widths([32, 32, 64, 64, 32, 16]);
        assert_ne!(slim, Widths::COMMITTED);
        let bytes = file_with_metadata(FORMAT, Decoder::Kernel, slim, &[], |_, _, _| true);
        let weights = NetworkWeights::from_bytes(&bytes, "w").expect("loads");
        assert_eq!(weights.widths(), slim);
        assert_eq!(
            weights.layers(),
            Decoder::Kernel.layers(slim, KERNEL_SCALES, false)
        );
        let dec0 = weights.layers()[5];
        assert_eq!((dec0.in0, dec0.in1, dec0.out), (32, 32, 16));
        assert!(weights.layers()[6..].iter().all(|head| head.in0 == 16));
        let floats: usize = weights.layers().iter().map(Layer::packed_len).sum();
        assert_eq!(weights.packed().len(), floats);

        // A head that reads other channels than dec0 writes.
        let mismatched =
            file_with_metadata(FORMAT, Decoder::Kernel, slim, &[], |name, shape, values| {
                if name == "out_half.weight" {
                    shape[1] = 32;
                    values.resize(shape.iter().product(), 0.5);
                }
                true
            });
        let message = error(&mismatched);
        assert!(
            message.contains("out_half.weight") && message.contains("expected [26, 16, 3, 3]"),
            "{message}"
        );
        // A width the tensor-core tiles do not divide.
        let odd = file(FORMAT, |name, shape, values| {
            if name == "enc1.weight" {
                shape[0] = 24;
                values.truncate(shape.iter().product());
            }
            true
        });
        let message = error(&odd);
        assert!(
            message.contains("enc1.weight") && message.contains("24 output channels"),
            "{message}"
        );
    }

    #[test]
    fn output_channels_are_padded_with_zeros() {
        let kernel = file_for(FORMAT, Decoder::Kernel, |_, _, _| true);
        let weights = NetworkWeights::from_bytes(&kernel, "w").expect("loads");
        let index = weights.layers().iter().position(|l| l.name == "out_half");
        let layer = weights.layers()[index.expect("has out_half")];
        assert_eq!((layer.out, layer.out_padded()), (26, 28));
        let start = weights.offset(index.expect("index")) as usize * 4;
        let packed = &weights.packed()[start..start + layer.packed_len()];
        for (i, chunk) in packed.chunks(28).enumerate() {
            assert!(chunk[..26].iter().all(|&w| w == 0.5), "row {i}");
            assert_eq!(chunk[26..], [0.0, 0.0], "row {i}");
        }
    }

    #[test]
    fn bad_files_name_the_file_and_the_tensor() {
        let good = file(FORMAT, |_, _, _| true);
        let truncated = error(&good[..good.len() / 2]);
        assert!(
            truncated.contains("w.safetensors") && truncated.contains("not a valid safetensors")
        );
        assert!(error(b"not a weights file").contains("not a valid safetensors"));
        assert!(error(&file("lucid-rae-v2", |_, _, _| true)).contains("format \"lucid-rae-v2\""));
        let mut other = file(FORMAT, |_, _, _| true);
        let at = other
            .windows(6)
            .position(|w| w == b"direct")
            .expect("decoder in the header");
        other[at..at + 6].copy_from_slice(b"dirext");
        assert!(error(&other).contains("decoder \"dirext\""));
        let missing = error(&file(FORMAT, |name, _, _| name != "dec1.bias"));
        assert!(
            missing.contains("dec1.bias") && missing.contains("missing"),
            "{missing}"
        );
        let shape = error(&file(FORMAT, |name, shape, values| {
            if name == "enc0.weight" {
                shape[1] = 8;
                values.truncate(shape.iter().product());
            }
            true
        }));
        assert!(
            shape.contains("enc0.weight") && shape.contains("shape"),
            "{shape}"
        );
        let nan = error(&file(FORMAT, |name, _, values| {
            if name == "out.bias" {
                values[2] = f32::NAN;
            }
            true
        }));
        assert!(nan.contains("out.bias") && nan.contains("NaN"), "{nan}");
    }
}
