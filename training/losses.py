"""Training losses and the validation metrics that are not one line.

Predictions and references are linear radiance, [B, T, 3, H, W] (a window of frames).

- `l1grad` (the default): 0.8 spatial L1 + 0.1 gradient L1 + 0.1 temporal L1 on frame differences,
  in log space (Chaitanya et al. 2017).
- `l1msssim`: 0.16 L1 + 0.84 (1 - MS-SSIM) on display-mapped images (Zhao et al. 2017, "Loss
  functions for image restoration with neural networks"), plus the same temporal term in log space.
- `l1gradflip`: `l1grad`'s three terms plus FLIP (`flip.py`) on the display-mapped frames, the
  metric the held-out evaluation reports, weighted 0.5.

All weight later frames of a window more (the recurrence has warmed up), unless called with
`flat=True` (a window that starts at a cut, whose first frames matter as much).
"""

import torch
import torch.nn.functional as F

from flip import Flip

LOSSES = ("l1grad", "l1msssim", "l1gradflip")
DEFAULT_WEIGHTS = {"l1grad": (0.8, 0.1, 0.1), "l1msssim": (0.16, 0.84, 0.1), "l1gradflip": (0.8, 0.1, 0.1, 0.5)}
TERM_NAMES = {
    "l1grad": ("spatial", "gradient", "temporal"),
    "l1msssim": ("l1", "msssim", "temporal"),
    "l1gradflip": ("spatial", "gradient", "temporal", "flip"),
}

# SSIM as `lucid evaluate` computes it (engine/src/metrics/ssim.rs): 11-tap Gaussian, sigma 1.5,
# K1 = 0.01, K2 = 0.03, dynamic range 1.
WINDOW = 11
SIGMA = 1.5
C1 = 0.01**2
C2 = 0.03**2
# MS-SSIM's scale weights (Wang et al. 2003); the first `scales` of them are used, renormalized.
MS_WEIGHTS = (0.0448, 0.2856, 0.3001, 0.2363, 0.1333)
REC709 = (0.2126, 0.7152, 0.0722)


def log_tonemap(x):
    """log(1 + x): the space the network predicts in and `l1grad` compares in."""
    return torch.log1p(x.clamp_min(0.0))


def aces(x):
    """Narkowicz's fit of the ACES filmic curve, as `lucid evaluate`'s display mapping uses it."""
    return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)


def srgb_encode(x):
    """The sRGB OETF on [0, 1] (the power branch clamped so its gradient stays finite)."""
    return torch.where(x <= 0.0031308, 12.92 * x, 1.055 * x.clamp_min(0.0031308) ** (1.0 / 2.4) - 0.055)


def display_linear(x):
    """Linear radiance to linear display light in [0, 1] (ACES, no sRGB encoding): what `lucid
    evaluate` gives FLIP."""
    return aces(x.clamp_min(0.0)).clamp(0.0, 1.0)


def display(x, clamp=True):
    """Linear radiance to display values: ACES then sRGB, what `lucid evaluate` compares SSIM on.
    With `clamp=False` (the loss) values above white keep ACES's slowly rising curve (up to 1.03)
    instead of being cut at 1, so bright pixels keep a gradient."""
    return srgb_encode(display_linear(x) if clamp else aces(x.clamp_min(0.0)))


_FLIPS = {}


def flip(pred, ref):
    """FLIP of each display-mapped frame of [N, 3, H, W] linear radiance against its reference: [N]."""
    if pred.device not in _FLIPS:
        _FLIPS[pred.device] = Flip(pred.device)
    return _FLIPS[pred.device](display_linear(pred), display_linear(ref))


def _frame_weights(t, device, flat=False):
    """The weights of a window's `t` frames: rising from 0.5 to 1.5, or all 1 if `flat`."""
    return torch.ones(t, device=device) if flat else torch.linspace(0.5, 1.5, t, device=device)


def temporal_l1(p, r):
    """Mean |(p[t] - p[t-1]) - (r[t] - r[t-1])| over a window ([B, T, ...], already tone-mapped)."""
    return ((p[:, 1:] - p[:, :-1]) - (r[:, 1:] - r[:, :-1])).abs().mean()


def gaussian_window(size, sigma, device, dtype=torch.float32):
    x = torch.arange(size, device=device, dtype=dtype) - (size - 1) / 2
    g = torch.exp(-(x * x) / (2 * sigma * sigma))
    return g / g.sum()


def _blur(x, g, pad):
    """Separable Gaussian blur of each channel of [N, C, H, W]; `pad` replicates the borders
    (output the input's size), otherwise only the fully covered ("valid") pixels are kept."""
    c = x.shape[1]
    k = g.numel()
    if pad:
        x = F.pad(x, (k // 2, k // 2, k // 2, k // 2), mode="replicate")
    x = F.conv2d(x, g.view(1, 1, 1, k).expand(c, 1, 1, k), groups=c)
    return F.conv2d(x, g.view(1, 1, k, 1).expand(c, 1, k, 1), groups=c)


def _ssim_maps(x, y, size, pad):
    """SSIM's luminance-contrast-structure map and its contrast-structure map."""
    g = gaussian_window(size, SIGMA, x.device)
    mx, my = _blur(x, g, pad), _blur(y, g, pad)
    vx = _blur(x * x, g, pad) - mx * mx
    vy = _blur(y * y, g, pad) - my * my
    cov = _blur(x * y, g, pad) - mx * my
    cs = (2 * cov + C2) / (vx + vy + C2)
    lum = (2 * mx * my + C1) / (mx * mx + my * my + C1)
    return lum * cs, cs


def _window_for(h, w):
    """The standard 11-tap window, shrunk (odd) where an image scale is smaller than it."""
    size = min(WINDOW, h, w)
    return size if size % 2 else size - 1


def ssim(x, y, pad=True):
    """Mean SSIM of each image of [N, C, H, W] (channels averaged): [N]. `pad=True` replicates the
    borders as `lucid evaluate` does."""
    s, _ = _ssim_maps(x, y, _window_for(*x.shape[-2:]), pad)
    return s.mean(dim=(1, 2, 3))


def ms_ssim(x, y, scales=3):
    """Multi-scale SSIM (Wang et al. 2003) of each image of [N, C, H, W], per channel then averaged:
    [N]. Contrast-structure terms at the finer scales, full SSIM at the coarsest, 2x2 average
    pooling between scales, "valid" windows, the first `scales` standard weights renormalized.
    Terms are clamped to at least 1e-4 before the fractional powers (finite gradients)."""
    weights = torch.tensor(MS_WEIGHTS[:scales], device=x.device)
    weights = weights / weights.sum()
    terms = []
    for i in range(scales):
        s, cs = _ssim_maps(x, y, _window_for(*x.shape[-2:]), pad=False)
        if i + 1 < scales:
            terms.append(cs.mean(dim=(2, 3)))
            x, y = F.avg_pool2d(x, 2), F.avg_pool2d(y, 2)
        else:
            terms.append(s.mean(dim=(2, 3)))
    t = torch.stack(terms, 0).clamp_min(1e-4)  # [scales, N, C]
    return torch.prod(t ** weights.view(-1, 1, 1), 0).mean(1)


def luminance(x):
    """Rec.709 weighted sum of the channels of [..., 3, H, W]: [..., 1, H, W]."""
    w = torch.tensor(REC709, device=x.device, dtype=x.dtype).view(3, 1, 1)
    return (x * w).sum(-3, keepdim=True)


def display_ssim(pred, ref):
    """SSIM per frame as `lucid evaluate` computes it: luminance of the display-mapped (ACES, sRGB)
    images, borders replicated. `pred`, `ref` linear [N, 3, H, W]; returns [N]."""
    return ssim(luminance(display(pred)), luminance(display(ref)), pad=True)


def l1grad(pred, ref, weights, flat=False):
    """Weighted sum and terms (spatial L1, gradient L1, temporal L1) in log space."""
    p, r = log_tonemap(pred), log_tonemap(ref)
    t = p.shape[1]
    wt = _frame_weights(t, p.device, flat).view(1, t, 1, 1, 1)
    spatial = (wt * (p - r).abs()).mean()
    gx = lambda x: x[..., :, 1:] - x[..., :, :-1]  # noqa: E731
    gy = lambda x: x[..., 1:, :] - x[..., :-1, :]  # noqa: E731
    grad = (gx(p) - gx(r)).abs().mean() + (gy(p) - gy(r)).abs().mean()
    temporal = temporal_l1(p, r)
    terms = (spatial, grad, temporal)
    return sum(w * x for w, x in zip(weights, terms)), terms


def l1msssim(pred, ref, weights, flat=False, scales=3):
    """Weighted sum and terms (L1 and 1 - MS-SSIM on display-mapped images, temporal L1 in log
    space)."""
    b, t = pred.shape[:2]
    wt = _frame_weights(t, pred.device, flat)
    dp, dr = display(pred, clamp=False), display(ref, clamp=False)
    l1 = (wt.view(1, t, 1, 1, 1) * (dp - dr).abs()).mean()
    ms = ms_ssim(dp.flatten(0, 1), dr.flatten(0, 1), scales).view(b, t)
    msssim = (wt.view(1, t) * (1.0 - ms)).mean()
    temporal = temporal_l1(log_tonemap(pred), log_tonemap(ref))
    terms = (l1, msssim, temporal)
    return sum(w * x for w, x in zip(weights, terms)), terms


def l1gradflip(pred, ref, weights, flat=False):
    """Weighted sum and terms: `l1grad`'s three, then FLIP of the display-mapped frames (later
    frames weighted more unless `flat`)."""
    _, terms = l1grad(pred, ref, weights[:3], flat)
    b, t = pred.shape[:2]
    per_frame = flip(pred.flatten(0, 1), ref.flatten(0, 1)).view(b, t)
    terms = (*terms, (_frame_weights(t, pred.device, flat).view(1, t) * per_frame).mean())
    return sum(w * x for w, x in zip(weights, terms)), terms


def loss_fn(name):
    """The loss function called `name` (one of `LOSSES`): f(pred, ref, weights, flat) -> (loss,
    terms)."""
    return {"l1grad": l1grad, "l1msssim": l1msssim, "l1gradflip": l1gradflip}[name]


def relmse(pred, ref):
    """Relative MSE with epsilon 0.01, as `lucid evaluate` computes it."""
    return ((pred - ref) ** 2 / (ref**2 + 1e-2)).mean()


# The brightness, in multiples of the reference's mean, from which `light_kept` counts (the
# brightest band of `lucid evaluate --maps`, `BRIGHTNESS_EDGES` in sandbox/src/cli/maps.rs).
BRIGHT = 8.0


def light_kept(pred, ref):
    """The share of the reference's light that `pred` keeps where the reference, averaged over the
    frames, is at least `BRIGHT` times its mean, as `lucid evaluate --maps` reports it (`light`, its
    brightest band): a denoiser that erases a caustic keeps much less than 1. `pred`, `ref` linear
    [N, 3, H, W], one sequence's frames; None where no pixel is that bright."""
    ref_lum = luminance(ref).mean(0)
    bright = ref_lum >= BRIGHT * ref_lum.mean()
    if not bright.any():
        return None
    return (luminance(pred).mean(0)[bright].sum() / ref_lum[bright].sum()).item()


# Side of the blocks `energy_l1` compares.
ENERGY_BLOCK = 8


def energy_l1(pred, ref):
    """L1 between log(1 + the 8x8 blocks' mean radiance) of `pred` and `ref` (linear [N, 3, H, W]):
    the light a block keeps, wherever in the block it lies. The log-space L1 of each pixel charges
    a caustic erased from a few pixels little; this charges it as the light the block lost."""
    blocks = lambda x: torch.log1p(F.avg_pool2d(x.clamp_min(0.0), ENERGY_BLOCK))  # noqa: E731
    return (blocks(pred) - blocks(ref)).abs().mean()


# Side of the blocks `worst_block_excess` compares (`BLOCK` in tests/tests/svgf_fireflies.rs).
BLOCK = 8


def worst_block_excess(pred, ref):
    """Per frame, the largest excess of an 8x8 block's mean luminance over the reference's,
    relative to the reference frame's mean luminance, as the lavapipe blotch test measures one frame
    (`worst_block_excess` in tests/tests/svgf_fireflies.rs): a firefly smeared into a blotch
    brightens a whole block. `pred`, `ref` linear [N, 3, H, W]; returns [N]."""
    blocks = lambda x: F.avg_pool2d(luminance(x), BLOCK)  # noqa: E731
    excess = (blocks(pred) - blocks(ref)).flatten(1).amax(1)
    return excess / luminance(ref).flatten(1).mean(1).clamp_min(1e-6)

