"""Lucid's recurrent denoising autoencoder (format `lucid-rae-v3`, direct-predicting decoder), the
PyTorch twin of the Vulkan inference in `passes/src/denoise/neural/` and `shaders/neural/`;
`kernel_model.py` holds its kernel-predicting decoder.

Everything the shaders compute is defined here, in the same order and with the same arithmetic:
the input features (with last frame's output and two running means of the noisy radiance, one of
it and one of it range-compressed against fireflies, warped by the motion vectors and masked where
reprojection fails), the U-Net of 3x3 convolutions, and the
output (a blend of the network's prediction with the warped history; with a weights file's
`atrous_steps`, blended per pixel, by a gate the network predicts, with its edge-aware a-trous
filtering, `atrous`; re-modulated by the first hits' albedo plus emission averaged over time with
the same warp's taps of the same object, `antialias_surface`). With
`fp16_storage=True` every tensor the shaders store in half precision is rounded to it here too,
so the parity test can compare tightly.

Per-pixel inputs (the "record", channels first, one frame): see `RECORD_CHANNELS`.
"""

import torch
import torch.nn as nn
import torch.nn.functional as F
from torch.utils.checkpoint import checkpoint

FORMAT = "lucid-rae-v3"
# The decoders a v3 file may hold (its `decoder` metadata): this file's and `kernel_model.py`'s.
DECODERS = ("direct", "kernel")

# The per-pixel inputs of a frame, in the order the dataset and the parity fixture store them.
RECORD_CHANNELS = {
    "demodulated": 3,  # (radiance - first-hit emission) / first-hit albedo, this frame's samples
    "albedo": 3,  # first-hit demodulation albedo
    "emission": 3,  # first-hit emission towards the camera
    "normal": 3,  # G-buffer world normal (facing the camera)
    "roughness": 1,  # G-buffer GGX alpha (1 for diffuse)
    "depth": 1,  # G-buffer view depth (0 where the sky is seen)
    "motion": 3,  # offset to last frame's pixel (xy), last frame's depth of the point (z)
}
RECORD_SIZE = sum(RECORD_CHANNELS.values())

FEATURES = 24  # a multiple of 4: the shaders pack 4 half-precision channels per uvec2
# The U-Net's hidden layers, in execution order, and the shipped network's widths (their output
# channels, multiples of 16): `unet_layers` derives every layer's inputs from the widths, so a
# network of other widths is the same code (the Vulkan inference reads them from the weights'
# shapes).
HIDDEN = ("enc0", "enc1", "enc2", "bottleneck", "dec1", "dec0")
WIDTHS = (16, 32, 64, 64, 32, 16)
# The output layer's channels: log radiance (3) and the blend weight's logit (and, with the gated
# a-trous filter, its gate's logit: one more).
OUTPUTS = 4


# What each hidden layer reads, in the order of its input channels (None: the input features); the
# output layers (`out`, and `kernel_model.py`'s heads) read the last one's, `dec0`'s.
SOURCES = {
    "enc0": (None,),
    "enc1": ("enc0",),
    "enc2": ("enc1",),
    "bottleneck": ("enc2",),
    "dec1": ("bottleneck", "enc1"),
    "dec0": ("dec1", "enc0"),
}


def sources(layer):
    """What `layer` reads ([`SOURCES`], or `dec0` for an output layer)."""
    return SOURCES.get(layer, ("dec0",))


def unet_layers(widths=WIDTHS, outputs=OUTPUTS, recurrent=0, extra=0):
    """(name, input channels, output channels) of the convolutions, in execution order, for the
    hidden layers' `widths` and `outputs` channels of the output layer; with `extra` channels of
    extra inputs (`EXTRA_INPUTS`), `enc0` reads them after the input features; with `recurrent`
    channels of recurrent state, `enc0` reads them after those and the layer `recurrent` (on
    `dec0`'s features, before `out`) writes them."""
    width = dict(zip(HIDDEN, widths))
    first = FEATURES + extra + recurrent  # what `enc0` reads
    inputs = lambda layer: sum(first if s is None else width[s] for s in sources(layer))  # noqa: E731
    state_layer = [("recurrent", inputs("recurrent"), recurrent)] if recurrent else []
    return [(name, inputs(name), width[name]) for name in HIDDEN] + state_layer + [("out", inputs("out"), outputs)]


# Channels of `motion_inputs` and of `noise_inputs`.
MOTION_INPUTS = 2
NOISE_INPUTS = 2
# The inputs `enc0` may read after the input features, in this order, and their channels: the
# reprojection's motion (`motion_inputs`, forty-fifth session) and the running means' own noise
# (`noise_inputs`, forty-ninth). A weights file names each it reads in its `<name>_inputs`
# metadata, the channels' count; none is in the committed weights.
EXTRA_INPUTS = {"motion": MOTION_INPUTS, "noise": NOISE_INPUTS}


def extras_of(names):
    """The extra inputs `names` (of `EXTRA_INPUTS`) in `enc0`'s order; an unknown name is an error."""
    unknown = sorted(set(names) - EXTRA_INPUTS.keys())
    if unknown:
        raise ValueError(f"unknown extra inputs {unknown}: known are {list(EXTRA_INPUTS)}")
    return tuple(name for name in EXTRA_INPUTS if name in names)


def extra_channels(extras):
    """The channels of the extra inputs `extras`."""
    return sum(EXTRA_INPUTS[name] for name in extras)


def motion_inputs(motion):
    """What the reprojection of the history does at each pixel, from the G-buffer's `motion`
    [B,3,H,W] (pixels to last frame's position, then the depth expected there): log(1 + its length
    in pixels), and how much its bilinear taps blur, 2 (fx (1 - fx) + fy (1 - fy)) with (fx, fy) the
    fractional offset (0 on whole pixels, 1 halfway in both). The history is resampled every frame:
    these say how fast the view moves and how much this frame's resampling softens the history."""
    m = motion[:, 0:2]
    frac = m - torch.floor(m)
    length = torch.log1p(torch.sqrt((m * m).sum(1, keepdim=True)))
    blur = 2.0 * (frac * (1.0 - frac)).sum(1, keepdim=True)
    return torch.cat([length, blur], 1)


def widths_of(tensors):
    """The hidden layers' widths of a weights file's `tensors` (name -> tensor)."""
    return tuple(int(tensors[f"{name}.weight"].shape[0]) for name in HIDDEN)


# Reprojection validity, as in SVGF's temporal pass (without its depth-slope term).
DEPTH_TOLERANCE = 0.05
NORMAL_COS = 0.9
MIN_WEIGHT = 0.01

# The running mean of the noisy radiance: what the network's input divides its history length by,
# and the longest history it may average (after that, an exponential moving average; a weights
# file's `history_frames` metadata can set fewer frames, the model's `history_frames`), and the
# luminance its moments are taken of (Rec. 709, `luminance` in shaders/common/math.glsl).
N_MAX = 32.0
# The first hits' albedo and emission that re-modulate the output are averaged over time as SVGF's
# temporal pass averages them, from taps of the same object: each frame's values weigh at least
# SURFACE_ALPHA, and this frame's emission at least EMISSION_MOTION times the pixel's motion in
# pixels (`antialias_surface`; 0 measured against 0.25 and 0.5 on the held-out paths once the
# taps had to be of the same object, training/README.md).
SURFACE_ALPHA = 0.1
EMISSION_MOTION = 0.0
# The history lengths below which the variance inputs are taken over the pixel's 3x3 neighbourhood
# of this frame's samples rather than over its history, as SVGF estimates them for its first four
# frames (`variances`; a weights file's `spatial_variance_frames` metadata, 0 where it has none:
# always over the history, 0 from one sample).
SPATIAL_VARIANCE_FRAMES = 0
# The bits of an object id the emission's history keeps in the shaders (exact in a float32).
OBJECT_BITS = 0xFFFFFF
LUMINANCE = (0.2126, 0.7152, 0.0722)
# The gated a-trous filter over the output's illumination (`atrous`; a weights file's
# `atrous_steps` metadata, comma-separated spacings in pixels, and then `out`'s last channel, the
# gate's logit): the 5x5 B-spline kernel's weights along each axis, the luminance agreement's
# relative tolerance and the normals' agreement's power (SVGF's), what a file's steps may be, and
# the gate's bias when weights without it start a model with it (sigmoid(-3): about 5% filtered
# everywhere, so that fine-tuning starts near the unfiltered output; `train.load_weights`).
B_SPLINE = (1 / 16, 1 / 4, 3 / 8, 1 / 4, 1 / 16)
ATROUS_SIGMA = 0.1
ATROUS_NORMAL_POWER = 128
ATROUS_MAX_STEP = 64
ATROUS_MAX_STEPS = 5
ATROUS_GATE_BIAS = -3.0


def split_record(record):
    """Splits a [..., RECORD_SIZE, H, W] tensor into a dict of named channel groups."""
    out, c = {}, 0
    for name, n in RECORD_CHANNELS.items():
        out[name] = record[..., c : c + n, :, :]
        c += n
    return out


def half(x, enabled):
    """Rounds to half precision (what a half-precision store does) when `enabled`."""
    return x.half().float() if enabled else x


def warp_history(history, prev_surface, motion, normal, depth, objects, surface_channels):
    """Bilinear reprojection of last frame's `history` [B,C,H,W] to this frame's pixels, each of
    the four taps kept only where last frame saw the same surface (depth within 5% of the depth
    the motion vectors expect, normals within about 25 degrees; sky only to sky). The last
    `surface_channels` of the history (the averaged albedo and emission) keep, of those taps, only
    the ones whose object (`prev_surface` channel 4) is this pixel's (`objects` [B,1,H,W]), and
    are normalised by their own weights. Returns the warped history, the validity mask [B,1,H,W]
    (1 where the taps' weights sum to at least 0.01) and the surface channels' own mask."""
    b, _, h, w = history.shape
    ys, xs = torch.meshgrid(
        torch.arange(h, device=history.device, dtype=torch.float32),
        torch.arange(w, device=history.device, dtype=torch.float32),
        indexing="ij",
    )
    px = xs + motion[:, 0]
    py = ys + motion[:, 1]
    bx = torch.floor(px)
    by = torch.floor(py)
    fx = px - bx
    fy = py - by
    expected = motion[:, 2]
    here_sky = depth[:, 0] <= 0.0
    prev_depth = prev_surface[:, 0:1]
    prev_normal = prev_surface[:, 1:4]
    prev_objects = prev_surface[:, 4:5]
    split = history.shape[1] - surface_channels
    acc = torch.zeros_like(history[:, :split])
    surface_acc = torch.zeros_like(history[:, split:])
    wsum = torch.zeros_like(expected)
    surface_wsum = torch.zeros_like(expected)
    for dx, dy in ((0, 0), (1, 0), (0, 1), (1, 1)):
        qx = bx + dx
        qy = by + dy
        wgt = (fx if dx else 1.0 - fx) * (fy if dy else 1.0 - fy)
        inside = (qx >= 0) & (qx < w) & (qy >= 0) & (qy < h)
        ix = qx.clamp(0, w - 1).long()
        iy = qy.clamp(0, h - 1).long()
        flat = (iy * w + ix).view(b, 1, -1)

        def gather(t):
            return torch.gather(t.reshape(b, t.shape[1], -1), 2, flat.expand(-1, t.shape[1], -1)).view(
                b, t.shape[1], h, w
            )

        q_depth = gather(prev_depth)[:, 0]
        q_normal = gather(prev_normal)
        q_hist = gather(history)
        q_sky = q_depth <= 0.0
        same = (torch.abs(q_depth - expected) <= DEPTH_TOLERANCE * expected) & (
            (q_normal * normal).sum(1) > NORMAL_COS
        )
        valid = inside & torch.where(here_sky, q_sky, (~q_sky) & same)
        wv = torch.where(valid, wgt, torch.zeros_like(wgt))
        acc = acc + wv.unsqueeze(1) * q_hist[:, :split]
        wsum = wsum + wv
        same_object = valid & (gather(prev_objects)[:, 0] == objects[:, 0])
        wo = torch.where(same_object, wgt, torch.zeros_like(wgt))
        surface_acc = surface_acc + wo.unsqueeze(1) * q_hist[:, split:]
        surface_wsum = surface_wsum + wo

    def normalised(total, weights):
        ok = weights >= MIN_WEIGHT
        return torch.where(ok.unsqueeze(1), total / weights.clamp_min(1e-8).unsqueeze(1), torch.zeros_like(total)), ok

    warped, ok = normalised(acc, wsum)
    warped_surface, surface_ok = normalised(surface_acc, surface_wsum)
    return torch.cat([warped, warped_surface], 1), ok.float().unsqueeze(1), surface_ok.float().unsqueeze(1)


def luminance(rgb):
    """Rec. 709 luminance of [B,3,H,W] -> [B,1,H,W], summed in the shader's order."""
    return rgb[:, 0:1] * LUMINANCE[0] + rgb[:, 1:2] * LUMINANCE[1] + rgb[:, 2:3] * LUMINANCE[2]


def compress(rgb):
    """Range compression against fireflies: rgb / (1 + luminance), whose luminance stays below 1
    however bright a sample is (Karis's weighting)."""
    return rgb / (1.0 + luminance(rgb))


def expand(rgb):
    """The inverse of `compress` (the luminance's distance to 1 kept at least 1e-3)."""
    return rgb / torch.clamp(1.0 - luminance(rgb), min=EXPAND_MIN)


# The smallest 1 - luminance `expand` divides by: compressed means map back to at most 1000.
EXPAND_MIN = 1e-3


def accumulate(demodulated, warped_accum, warped_moment, warped_robust, mask, history_frames=N_MAX):
    """This frame's running means of the noisy demodulated radiance, as SVGF's temporal pass keeps
    them: where reprojection holds (`mask`), the history length n = min(n' + 1, history_frames) of the
    warped length n', and every mean moves towards this frame's value by 1/n; elsewhere n = 1 and
    they are this frame's. Two means: of the radiance (with the second moment of its luminance)
    and, robust to fireflies, of the radiance range-compressed by `compress` (with the second
    moment of the compressed luminance). Returns (accum [B,4,H,W]: mean rgb and n; moment
    [B,1,H,W]; robust [B,4,H,W]: compressed mean rgb and second moment)."""
    current = demodulated.clamp_min(0.0)
    lum = luminance(current)
    squeezed = compress(current)
    squeezed_lum = luminance(squeezed)
    ok = mask > 0.0
    n = torch.where(ok, torch.clamp(warped_accum[:, 3:4] + 1.0, max=float(history_frames)), torch.ones_like(mask))
    alpha = 1.0 / n

    def toward(prev, value):
        return torch.where(ok, prev + (value - prev) * alpha, value)

    mean = toward(warped_accum[:, 0:3], current)
    moment = toward(warped_moment, lum * lum)
    robust = toward(warped_robust, torch.cat([squeezed, squeezed_lum * squeezed_lum], 1))
    return torch.cat([mean, n], 1), moment, robust


def neighbourhood_range(x):
    """The per-channel minimum and maximum of `x` [B,C,H,W] over each pixel's 3x3 neighbourhood
    (the pixels inside the image)."""
    return -F.max_pool2d(-x, 3, stride=1, padding=1), F.max_pool2d(x, 3, stride=1, padding=1)


def antialias_surface(rec, warped_albedo, warped_emission, n, mask, emission_motion=EMISSION_MOTION):
    """The first hits' albedo and emission that re-modulate this frame's output, averaged over
    time: each frame's samples are jittered over the pixel, so one frame's are aliased and change
    from frame to frame at texture, emitter and object edges (the output flickered there).

    Where taps of the same object were reprojected (`mask`), the warped albedo moves towards this
    frame's by max(1/n, SURFACE_ALPHA), n the running mean's history length this frame (as SVGF
    averages it). The emission, as log(1 + emission), the same way but with a weight of at least
    the pixel's motion in pixels times `emission_motion` (the model's: `EMISSION_MOTION` unless
    its weights file's metadata says otherwise), and its history clamped to the range of this
    frame's values over the pixel's 3x3 neighbourhood. Taps of another object would spread a
    light's edge onto the ceiling beside it under motion (with them, averaging the emission
    doubled the relMSE on `classroom`, training/README.md); a light switched off leaves no trail.
    Elsewhere both are this frame's. Returns (albedo, log emission), [B,3,H,W] each."""
    ok = mask > 0.0
    alpha = torch.clamp(1.0 / n, min=SURFACE_ALPHA)
    albedo = torch.where(ok, warped_albedo + (rec["albedo"] - warped_albedo) * alpha, rec["albedo"])
    emission = torch.log1p(rec["emission"])
    speed = torch.sqrt(rec["motion"][:, 0:1] ** 2 + rec["motion"][:, 1:2] ** 2)
    alpha_emission = torch.maximum(alpha, torch.clamp(speed * emission_motion, max=1.0))
    low, high = neighbourhood_range(emission)
    prev = torch.minimum(torch.maximum(warped_emission, low), high)
    # A weight of 1 (a pixel or more of motion) keeps this frame's emission exactly.
    averaged = ok & (alpha_emission < 1.0)
    return albedo, torch.where(averaged, prev + (emission - prev) * alpha_emission, emission)


def neighbourhood_variance(x):
    """The variance of `x` [B,1,H,W] over each pixel's 3x3 neighbourhood (the pixels inside the
    image)."""
    mean = F.avg_pool2d(x, 3, stride=1, padding=1, count_include_pad=False)
    square = F.avg_pool2d(x * x, 3, stride=1, padding=1, count_include_pad=False)
    return (square - mean * mean).clamp_min(0.0)


def variances(current, accum, moment, robust, spatial_variance_frames=SPATIAL_VARIANCE_FRAMES):
    """The variance of the luminance over the running mean's history, and that of the compressed
    luminance over the robust mean's, [B,1,H,W] each, for `features` and `noise_inputs`: 0 from one
    sample; where the history length is below `spatial_variance_frames` those of this frame's
    samples `current` over the pixel's 3x3 neighbourhood (`neighbourhood_variance`)."""
    mean, n = accum[:, 0:3], accum[:, 3:4]
    mean_lum = luminance(mean)
    zero = torch.zeros_like(n)
    variance = torch.where(n > 1.0, (moment - mean_lum * mean_lum).clamp_min(0.0), zero)
    robust_lum = luminance(robust[:, 0:3])
    robust_variance = torch.where(n > 1.0, (robust[:, 3:4] - robust_lum * robust_lum).clamp_min(0.0), zero)
    if spatial_variance_frames > 0:
        spatial = n < float(spatial_variance_frames)
        variance = torch.where(spatial, neighbourhood_variance(luminance(current)), variance)
        squeezed = luminance(compress(current))
        robust_variance = torch.where(spatial, neighbourhood_variance(squeezed), robust_variance)
    return variance, robust_variance


def noise_inputs(accum, variance, robust_variance):
    """How far each running mean may still be from the truth: the standard deviations of `features`
    (from `variances`) divided by sqrt(n), n the history length (`accum`'s last channel): log(1 +
    that of the luminance) and that of the compressed luminance. The network sees the deviations
    and n / N_MAX apart, and the deviation of the samples does not fall as the history grows,
    while the mean's noise does."""
    n = accum[:, 3:4].clamp_min(1.0)
    return torch.cat([torch.log1p(torch.sqrt(variance / n)), torch.sqrt(robust_variance / n)], 1)


def features(rec, warped, mask, accum, robust, variance, robust_variance):
    """The network's 24 input channels for one frame: 15 as in `lucid-rae-v1` (log radiance,
    albedo, normal, roughness, log depth, warped output, mask), then log(1 + running mean) (3),
    its history length / N_MAX and log(1 + the standard deviation of luminance over it) as in v2,
    then log(1 + the robust mean expanded back) (3) and the standard deviation of the compressed
    luminance; the variances are `variances`'."""
    current = rec["demodulated"].clamp_min(0.0)
    mean, n = accum[:, 0:3], accum[:, 3:4]
    return torch.cat(
        [
            torch.log1p(current),
            rec["albedo"],
            rec["normal"],
            rec["roughness"],
            torch.log1p(rec["depth"].clamp_min(0.0)),
            warped,
            mask,
            torch.log1p(mean),
            n / N_MAX,
            torch.log1p(torch.sqrt(variance)),
            torch.log1p(expand(robust[:, 0:3])),
            torch.sqrt(robust_variance),
        ],
        dim=1,
    )


def atrous_steps_of(text):
    """The a-trous spacings of an `atrous_steps` metadata entry or option ("4,8,16": powers of two
    of pixels, 1 to ATROUS_MAX_STEP, which the renderer's tiles in shared memory need; 1 to
    ATROUS_MAX_STEPS of them); () for an empty one."""
    if not text:
        return ()
    try:
        steps = tuple(int(s) for s in text.split(","))
    except ValueError:
        raise ValueError(f"atrous steps '{text}' are not comma-separated whole numbers") from None
    if len(steps) > ATROUS_MAX_STEPS or not all(1 <= s <= ATROUS_MAX_STEP and s & (s - 1) == 0 for s in steps):
        raise ValueError(
            f"atrous steps '{text}': 1 to {ATROUS_MAX_STEPS} spacings of 1 to {ATROUS_MAX_STEP} pixels, powers of two"
        )
    return steps


def atrous_taps(t, step):
    """The 5x5 taps of `t` [B,C,H,W] `step` pixels apart, borders replicated: [B,C,25,H,W]."""
    b, c, h, w = t.shape
    pad = 2 * step
    padded = F.pad(t, (pad, pad, pad, pad), mode="replicate")
    return F.unfold(padded, len(B_SPLINE), dilation=step).view(b, c, len(B_SPLINE) ** 2, h, w)


def atrous_normal_weights(normal, step):
    """The weights of `atrous`'s taps `step` pixels apart that do not depend on the image: the
    B-spline's times the normals' agreement, [B,25,H,W] for the unit normals `normal`."""
    kernel = torch.tensor([ky * kx for ky in B_SPLINE for kx in B_SPLINE], device=normal.device).view(1, -1, 1, 1)
    return kernel * (normal.unsqueeze(2) * atrous_taps(normal, step)).sum(1).clamp_min(0.0) ** ATROUS_NORMAL_POWER


def atrous_step(x, normal_weights, step):
    """One step of `atrous` over `x` [B,3,H,W], its taps `step` pixels apart, `normal_weights`
    theirs from `atrous_normal_weights`."""
    centre = luminance(x)
    tap_lum = atrous_taps(centre, step)[:, 0]
    w_lum = torch.exp(-(tap_lum - centre).abs() / (ATROUS_SIGMA * centre + 1e-4))
    weight = normal_weights * w_lum
    total = (weight.unsqueeze(1) * atrous_taps(x, step)).sum(2)
    weights = weight.sum(1, keepdim=True)
    return torch.where(weights > 1e-12, total / weights.clamp_min(1e-12), x)


def atrous(illumination, normal, steps):
    """The edge-aware a-trous steps (SVGF's filter without its variance) over `illumination`
    [B,3,H,W], float32: per spacing s of `steps`, in order, each pixel p becomes the mean of the
    5x5 taps q at (i - 2, j - 2) * s (clamped into the image, as replicate padding does), weighed
    by B_SPLINE[i] * B_SPLINE[j], by the agreement of the normals (`normal` [B,3,H,W], normalised
    here; max(n_p . n_q, 0)^ATROUS_NORMAL_POWER, so a pixel without a normal keeps its value) and
    by that of the luminance, exp(-|l_q - l_p| / (ATROUS_SIGMA l_p + 1e-4)); a pixel whose weights
    sum to 1e-12 or less keeps its value. Each step gathers its 25 taps at once (a loop over them
    made a training step twice as slow) and is recomputed in the backward pass rather than keeping
    its taps (which took 10 GiB more to train on windows of 8 frames of 4 crops of 368x368); the
    weights of the normals, which need no gradient, are computed once outside it (on the CPU
    that made two steps' forward and backward 2.6 times as fast)."""
    x = illumination.float()
    normal = normal.float()
    normal = normal / normal.norm(dim=1, keepdim=True).clamp_min(1e-6)
    for step in steps:
        with torch.no_grad():
            normal_weights = atrous_normal_weights(normal, step)
        x = checkpoint(atrous_step, x, normal_weights, step, use_reentrant=False)
    return x


def pool(x):
    """2x2 average (sizes divisible by 4 in training; the shader clamps odd edges)."""
    return F.avg_pool2d(x, 2)


def up(x):
    """Nearest-neighbour 2x upsampling."""
    return F.interpolate(x, scale_factor=2, mode="nearest")


class RecurrentDenoiser(nn.Module):
    """The U-Net of `unet_layers(widths)` and the recurrent output blend; with `atrous_steps`
    (non-empty) the output layer has one more channel, the last, the logit of the gate of the
    `atrous` filter over the output; with `recurrent` > 0, that many channels of recurrent state
    (tanh of the layer `recurrent` on `dec0`'s features), warped with the output's history and
    read by `enc0` beside the input features in the next frame (zero in the first); `enc0` also
    reads the `extras` of `EXTRA_INPUTS` after the input features."""

    def __init__(self, widths=WIDTHS, atrous_steps=(), recurrent=0, extras=()):
        super().__init__()
        self.widths = tuple(widths)
        self.gate = bool(atrous_steps)
        self.recurrent = recurrent
        # The extra inputs `enc0` reads after the input features, in its order.
        self.extras = extras_of(extras)
        self.layers = unet_layers(self.widths, OUTPUTS + self.gate, recurrent, extra_channels(self.extras))
        self.convs = nn.ModuleDict({name: nn.Conv2d(cin, cout, 3, padding=1) for name, cin, cout in self.layers})
        # `antialias_surface`'s weight of this frame's emission per pixel of motion (the weights
        # file's `emission_motion` metadata).
        self.emission_motion = EMISSION_MOTION
        # `accumulate`'s longest history (the weights file's `history_frames` metadata).
        self.history_frames = int(N_MAX)
        # The history lengths whose variance inputs are spatial (`features`; the weights file's
        # `spatial_variance_frames` metadata).
        self.spatial_variance_frames = SPATIAL_VARIANCE_FRAMES
        # The spacings of the gated `atrous` filter's steps (the weights file's `atrous_steps`
        # metadata); () without the gate.
        self.atrous_steps = tuple(atrous_steps)

    def step(self, record, state, fp16_storage=False, objects=None):
        """One frame. `record` [B,RECORD_SIZE,H,W]; `objects` [B,1,H,W] the object id of each
        pixel's first hit (masked by OBJECT_BITS, as the dataset's `objects` are; None: all one
        object); `state` None (no history) or the dict returned by the previous step
        (`output`: log radiance [B,3], `surface`: depth, normal and object [B,5],
        `accum`: running mean and its length [B,4], `moment`: second moment of luminance [B,1],
        `robust`: the compressed running mean and its second moment [B,4], `albedo` and
        `emission`: the first hits' albedo and log(1 + emission) averaged over time [B,3] each;
        with recurrent state, `recurrent` [B,self.recurrent]).
        With the gate, the radiance's illumination is blended per pixel with its `atrous` filtering
        by sigmoid(the gate's logit); the state keeps the unfiltered output, the history the
        network reprojects. Returns (radiance [B,3,H,W], new state)."""
        rec = split_record(record)
        if objects is None:
            objects = torch.zeros_like(rec["depth"])
        k = self.recurrent
        if state is None:
            zero = torch.zeros_like(rec["depth"])
            warped, mask = torch.zeros_like(rec["demodulated"]), zero
            warped_accum, warped_moment = torch.zeros_like(record[:, 0:4]), zero
            warped_robust = torch.zeros_like(record[:, 0:4])
            surface_mask = zero
            warped_albedo = torch.zeros_like(rec["albedo"])
            warped_emission = torch.zeros_like(rec["emission"])
            warped_recurrent = zero.expand(-1, k, -1, -1)
        else:
            # One warp (the same taps and mask) for the output, the running means, the recurrent
            # state and, from the taps of the same object, the albedo and emission.
            names = ("output", "accum", "moment", "robust") + (("recurrent",) if k else ()) + ("albedo", "emission")
            history = torch.cat([state[n] for n in names], 1)
            history, mask, surface_mask = warp_history(
                history, state["surface"], rec["motion"], rec["normal"], rec["depth"], objects, 6
            )
            warped, warped_accum = history[:, 0:3], history[:, 3:7]
            warped_moment, warped_robust = history[:, 7:8], history[:, 8:12]
            warped_recurrent = history[:, 12 : 12 + k]
            warped_albedo, warped_emission = history[:, 12 + k : 15 + k], history[:, 15 + k : 18 + k]
        # The accumulation depends on the records only (no weights): no gradient through it.
        accum, moment, robust = accumulate(
            rec["demodulated"],
            warped_accum.detach(),
            warped_moment.detach(),
            warped_robust.detach(),
            mask,
            self.history_frames,
        )
        albedo, emission = antialias_surface(
            rec, warped_albedo.detach(), warped_emission.detach(), accum[:, 3:4], surface_mask, self.emission_motion
        )
        current = rec["demodulated"].clamp_min(0.0)
        variance, robust_variance = variances(current, accum, moment, robust, self.spatial_variance_frames)
        x = half(features(rec, warped, mask, accum, robust, variance, robust_variance), fp16_storage)
        warped, mask = x[:, 11:14], x[:, 14:15]  # as the output pass reads them: stored
        extra_inputs = {
            "motion": lambda: motion_inputs(rec["motion"]),
            "noise": lambda: noise_inputs(accum, variance, robust_variance),
        }
        for name in self.extras:
            x = torch.cat([x, half(extra_inputs[name](), fp16_storage)], 1)
        x = torch.cat([x, half(warped_recurrent, fp16_storage)], 1)
        c = self.convs
        r = lambda t: half(F.relu(t), fp16_storage)  # noqa: E731
        e0 = r(c["enc0"](x))
        e1 = r(c["enc1"](half(pool(e0), fp16_storage)))
        e2 = r(c["enc2"](half(pool(e1), fp16_storage)))
        b = r(c["bottleneck"](e2))
        d1 = r(c["dec1"](torch.cat([up(b), e1], 1)))
        d0 = r(c["dec0"](torch.cat([up(d1), e0], 1)))
        recurrent = half(torch.tanh(c["recurrent"](d0)), fp16_storage) if k else None
        o = half(self.predict(d0, rec, accum, fp16_storage), fp16_storage)
        blend = mask * torch.sigmoid(o[:, 3:4])
        log_out = (o[:, 0:3] * (1.0 - blend) + warped * blend).clamp_min(0.0)
        log_out = half(log_out, fp16_storage)
        illumination = torch.expm1(log_out)
        if self.gate:
            gate = torch.sigmoid(o[:, -1:].float())
            illumination = illumination.float()
            filtered = atrous(illumination, rec["normal"], self.atrous_steps)
            illumination = illumination + gate * (filtered - illumination)
        radiance = illumination * albedo + torch.expm1(emission)
        surface = torch.cat([rec["depth"], rec["normal"], objects], 1)
        state = {
            "output": log_out,
            "surface": surface,
            "accum": accum,
            "moment": moment,
            "robust": robust,
            "albedo": albedo,
            "emission": emission,
        }
        if k:
            state["recurrent"] = recurrent
        return radiance, state

    def predict(self, d0, rec, accum, fp16_storage):
        """The output layer on the last decoder features `d0` [B,widths[-1],H,W]: log radiance (3), the
        blend weight's logit (1) and, with the gate, the gate's logit (1). `rec` (the frame's record,
        split) and `accum` (its running mean and length) serve output layers that filter the
        radiance (`kernel_model.py`)."""
        return self.convs["out"](d0)

    @property
    def EXTRA_MACS_PER_PIXEL(self):
        """Multiply-adds per pixel outside the convolutions: each `atrous` step's 25 taps, each
        a normals' dot product and a weighted sum of 3 channels."""
        return len(self.atrous_steps) * len(B_SPLINE) ** 2 * 6.0

    def forward(self, records, fp16_storage=False, objects=None):
        """A sequence [B,T,RECORD_SIZE,H,W] from no history, its pixels' object ids `objects`
        [B,T,1,H,W] (None: all one object); returns [B,T,3,H,W]."""
        state, outs = None, []
        for t in range(records.shape[1]):
            frame_objects = None if objects is None else objects[:, t]
            y, state = self.step(records[:, t], state, fp16_storage, objects=frame_objects)
            outs.append(y)
        return torch.stack(outs, 1)


def export_tensors(model):
    """The weights as the Vulkan inference loads them: `<layer>.weight` [out,in,3,3] and
    `<layer>.bias` [out], float32."""
    return {
        f"{name}.{kind}": getattr(model.convs[name], kind).detach().float().cpu().contiguous()
        for name, _, _ in model.layers
        for kind in ("weight", "bias")
    }
