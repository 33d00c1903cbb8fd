"""The kernel-predicting decoder of the recurrent denoiser (format `lucid-rae-v3` with `decoder`
metadata `kernel`), measured against the direct-predicting `model.RecurrentDenoiser`; the Vulkan
inference runs both (`shaders/neural/kernel*` and `output.comp` for this one).

Everything but the output layer is `model.py`'s: the input features, the reprojected history, the
U-Net convolutions of `model.unet_layers` up to `dec0`, the temporal blend with the warped history and
the recurrent state. The output layer `out` is replaced by `KernelOutput`:

- **Scales** (Vogels et al. 2018, "Denoising with kernel prediction and asymmetric loss
  functions"; `scales`, three to five, the committed network four): the demodulated radiance at
  full resolution, average-pooled 2x2 (half), 4x4 (quarter), with four scales 8x8 (eighth) and
  with five 16x16 (sixteenth), each as log(1 + radiance) (pooled in linear space, then the log),
  so that the coarser scales gather 4, 16, 64 and 256 samples per pixel of a 1-sample frame.
- **Kernels from pooled decoder features**: the last decoder features (`dec0`, full resolution)
  go through a 3x3 convolution head a scale: `out` on them at full resolution, `out_half` on them
  average-pooled to half resolution, `out_quarter` on them pooled again to quarter resolution (and
  `out_eighth`, `out_sixteenth`). Each head predicts the 25 weights of a 5x5 kernel per pixel (softmax, so the
  filter is a weighted mean; borders replicate), applied to the log radiance of its scale.
- **Coarse-to-fine**: `fine' = fine - a * U(D(fine)) + a * U(coarse)` with D the 2x2 average, U
  bilinear upsampling and `a = sigmoid(.)` a per-pixel weight predicted by the finer scale's head
  (`out_half` for quarter into half, `out` for half into full): the coarse result replaces the
  fine result's low frequencies where `a` is 1.
- **Linear mix** (thirty-fourth session, optional: a file whose `out` has one channel more): a
  log-space mean of a bright, rare sample and its dark neighbours keeps almost none of its light
  (a caustic at 1 sample per pixel is such samples), a linear mean keeps all of it and every
  firefly too. With `linear_mix` the kernels and the compositing run twice, on log(1 + radiance)
  and on the radiance itself (the expansion of the same rounded log values), and `out`'s channel
  after the model's other outputs (`LINEAR_MIX_CHANNEL`, the last but for the gate) weighs the
  two per pixel: `log = log + m * (log(1 + max(linear, 0)) - log)`, `m = sigmoid(.)`.
- **The gate** (optional: a file with `atrous_steps` metadata): `out`'s last channel is the logit
  of the gate of `model.atrous`'s filter over the output, which `KernelOutput` returns after the
  other outputs, as the direct model's `out` does, and `RecurrentDenoiser.step` applies.
- **The rest as `model.py`**: `out`'s remaining channels are the direct model's output channels
  after its 3 radiance channels (the blend weight, and any later additions): the combined kernel
  result takes the place of the predicted log radiance, and `RecurrentDenoiser.step` does the
  rest (blend with the warped history, re-modulation, the state). The model subclasses it and only
  swaps its output layer (`predict`), so it keeps `step`/`forward` and the state as `model.py`
  defines them.

Export (`export_tensors`): the layers of `model.unet_layers` under their names (`out` with its
25 + 1 + EXTRA channels, one more with the linear mix and one more with the gate) plus the
coarser heads (`heads`), float32.

With `fp16_storage` the heads' outputs are rounded to half precision, as the shaders store them;
the filtered scales stay float32, as the shaders keep them.
"""

import torch
import torch.nn as nn
import torch.nn.functional as F

from model import WIDTHS, RecurrentDenoiser, extra_channels, half, pool, unet_layers

KERNEL = 5
TAPS = KERNEL * KERNEL
# The direct model's output channels after the 3 radiance channels (blend weight, ...), without
# the gate.
EXTRA = unet_layers()[-1][2] - 3
# The linear mix's channel of `out`, when it has one: after the kernel, the weight `a` and EXTRA
# (and before the gate).
LINEAR_MIX_CHANNEL = TAPS + 1 + EXTRA


# The bias of the linear mix's logit when weights without it start a model with it: sigmoid(-3), so
# that the mix starts at about 5% linear everywhere (`train.load_weights`).
LINEAR_MIX_BIAS = -3.0


# The kernel heads' names, finest first; a network has the first `scales` of them (by default the
# committed network's 4, since the twentieth session; 3 before).
HEAD_NAMES = ("out", "out_half", "out_quarter", "out_eighth", "out_sixteenth")
SCALES = 4


def heads(features, scales=SCALES, linear_mix=False, gate=False):
    """(name, input channels, output channels, resolution divisor) of the kernel heads on
    `features` channels of decoder features: each predicts its 25 kernel logits, every one but the
    coarsest the weight `a` of the next coarser scale, and the finest the model's other outputs,
    with `linear_mix` the logit of the linear mix and, with `gate`, last, the logit of the gate of
    the a-trous filter (`model.atrous`)."""
    if not 3 <= scales <= len(HEAD_NAMES):
        raise ValueError(f"{scales} scales: the kernel decoder has 3 to {len(HEAD_NAMES)}")
    return [
        (name, features, TAPS + (s < scales - 1) + ((EXTRA + linear_mix + gate) if s == 0 else 0), 2**s)
        for s, name in enumerate(HEAD_NAMES[:scales])
    ]


def scales_of(names):
    """How many scales a weights file's tensor `names` hold."""
    return max(s + 1 for s, name in enumerate(HEAD_NAMES) if f"{name}.weight" in names)


def linear_mix_of(out_channels, scales, gate=False):
    """Whether a weights file whose `out` head has `out_channels` (of a network of `scales`, with
    the gate if `gate`: its `atrous_steps` metadata) has the linear mix."""
    return out_channels == heads(1, scales, linear_mix=True, gate=gate)[0][2]


def apply_kernel(x, logits):
    """Filters `x` [B,C,H,W] with the per-pixel 5x5 kernels whose weights are softmax(`logits`)
    [B,25,H,W] (taps row-major, borders replicated). Float32."""
    b, c, h, w = x.shape
    r = KERNEL // 2
    weights = torch.softmax(logits.float(), 1)
    taps = F.unfold(F.pad(x.float(), (r, r, r, r), mode="replicate"), KERNEL)  # [B, C*25, H*W]
    return (taps.view(b, c, TAPS, h, w) * weights.unsqueeze(1)).sum(2)


def upsample(x, size):
    return F.interpolate(x, size=size, mode="bilinear", align_corners=False)


def combine(fine, coarse, a):
    """Vogels et al.'s scale compositing: the low frequencies of `fine` replaced by `coarse` where
    the per-pixel weight `a` is 1."""
    size = fine.shape[-2:]
    return fine + a * (upsample(coarse, size) - upsample(pool(fine), size))


class KernelOutput(nn.Module):
    """Stands in for the direct model's `out` convolution: called with the last decoder features
    and this frame's demodulated radiance, returns what `out` returns (log
    radiance in channels 0-2, then the other output channels, with `gate` the gate's logit last),
    the radiance here being the multi-scale kernel-filtered input."""

    def __init__(self, features, scales=SCALES, linear_mix=False, gate=False):
        super().__init__()
        self.scales = scales
        self.linear_mix = linear_mix
        self.gate = gate
        self.heads = nn.ModuleDict(
            {
                name: nn.Conv2d(cin, cout, 3, padding=1)
                for name, cin, cout, _ in heads(features, scales, linear_mix, gate)
            }
        )

    def forward(self, d0, radiance, fp16):
        radiance = [radiance.float().clamp_min(0.0)]
        features = [d0]
        for _ in range(1, self.scales):
            radiance.append(pool(radiance[-1]))
            features.append(half(pool(features[-1]), fp16))
        logits = [half(head(f), fp16) for head, f in zip(self.heads.values(), features)]
        y = linear = None
        for r, o in reversed(list(zip(radiance, logits))):
            log_r = half(torch.log1p(r), fp16)
            filtered = apply_kernel(log_r, o[:, :TAPS])
            filtered_linear = apply_kernel(torch.expm1(log_r.float()), o[:, :TAPS]) if self.linear_mix else None
            if y is None:
                y, linear = filtered, filtered_linear
            else:
                a = torch.sigmoid(o[:, TAPS : TAPS + 1].float())
                y = combine(filtered, y, a)
                linear = combine(filtered_linear, linear, a) if self.linear_mix else None
        extra = logits[0][:, TAPS + 1 : TAPS + 1 + EXTRA].float()
        if self.linear_mix:
            m = torch.sigmoid(logits[0][:, LINEAR_MIX_CHANNEL : LINEAR_MIX_CHANNEL + 1].float())
            y = y + m * (torch.log1p(linear.clamp_min(0.0)) - y)
        if self.gate:
            return torch.cat([y, extra, logits[0][:, -1:].float()], 1)
        return torch.cat([y, extra], 1)


class KernelDenoiser(RecurrentDenoiser):
    """`RecurrentDenoiser` with the kernel-predicting output layer; same `step`, `forward`, state."""

    def __init__(self, widths=WIDTHS, scales=SCALES, linear_mix=False, atrous_steps=(), recurrent=0, extras=()):
        super().__init__(widths, atrous_steps, recurrent, extras)
        self.convs["out"] = KernelOutput(self.widths[-1], scales, linear_mix, self.gate)

    @property
    def scales(self):
        return self.convs["out"].scales

    @property
    def linear_mix(self):
        return self.convs["out"].linear_mix

    def predict(self, d0, rec, accum, fp16_storage):
        return self.convs["out"](d0, rec["demodulated"], fp16_storage)

    def named_convs(self):
        """Every convolution under its export name."""
        convs = {name: self.convs[name] for name, _, _ in self.layers if name != "out"}
        convs.update(self.convs["out"].heads.items())
        return convs

    @property
    def EXTRA_MACS_PER_PIXEL(self):
        """Multiply-adds per full-resolution pixel outside the convolutions: a 5x5 filter on 3
        channels at each scale (1, 1/4, 1/16... of the pixels) and a compositing step into each
        but the coarsest (twice each with the linear mix), and the a-trous filter's
        (`RecurrentDenoiser.EXTRA_MACS_PER_PIXEL`)."""
        shares = [4.0**-s for s in range(self.scales)]
        kernels = (1 + self.linear_mix) * (3 * TAPS * sum(shares) + 3 * 2 * sum(shares[:-1]))
        return kernels + super().EXTRA_MACS_PER_PIXEL


def kernel_layers(widths=WIDTHS, scales=SCALES, linear_mix=False, gate=False, recurrent=0, extras=()):
    """(name, input channels, output channels) of every exported layer of a network of `widths`,
    `scales`, `linear_mix`, `gate`, `recurrent` channels of recurrent state and the extra inputs
    `extras` (`model.EXTRA_INPUTS`), in execution order."""
    unet = unet_layers(widths, recurrent=recurrent, extra=extra_channels(extras))
    layers = [(n, cin, cout) for n, cin, cout in unet if n != "out"]
    return layers + [(n, cin, cout) for n, cin, cout, _ in heads(widths[-1], scales, linear_mix, gate)]


def export_tensors(model):
    """`<layer>.weight` [out,in,3,3] and `<layer>.bias` [out], float32, for every layer of
    `kernel_layers()`."""
    return {
        f"{name}.{kind}": getattr(conv, kind).detach().float().cpu().contiguous()
        for name, conv in model.named_convs().items()
        for kind in ("weight", "bias")
    }
