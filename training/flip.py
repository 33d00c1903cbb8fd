"""LDR-FLIP (Andersson et al. 2020) in PyTorch, differentiable: the metric `lucid evaluate` reports
(engine/src/metrics/flip/), as a training loss and a validation metric.

It follows the engine's implementation step by step: YCxCz opponent colours, contrast-sensitivity
filters for the viewing distance (borders replicated), Hunt-adjusted L*a*b* compared by HyAB,
compressed and remapped; edge and point detectors on the luminance; per pixel
colour_error ^ (1 - feature_error). Inputs are linear display light in [0, 1] (`lucid evaluate`
gives FLIP its ACES-mapped frames, before the sRGB encoding). Where the metric's functions have
infinite slopes at zero (the HyAB chroma distance, the 0.7 and 0.5 powers, the final power) a
small epsilon keeps the gradient finite; the value moves by less than 1e-3.
"""

import math

import torch
import torch.nn.functional as F

PIXELS_PER_DEGREE = 3840.0 * math.pi / 180.0

_RGB_TO_XYZ = (
    (10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0),
    (2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0),
    (1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0),
)
_XYZ_TO_RGB = (
    (3.2410033, -1.5373989, -0.49861586),
    (-0.9692243, 1.8759301, 0.041554224),
    (0.055639423, -0.2040112, 1.0571489),
)
_WHITE = (0.9504285, 1.0, 1.0889004)
# The colour pipeline's compression (QC), knee (PC) and the share of [0, 1] below it (PT).
_QC, _PC, _PT = 0.7, 0.4, 0.95
# CSF scale parameters: achromatic, red-green, and the blue-yellow pair of (a, b) terms.
_CSF_A_B, _CSF_RG_B = 0.0047, 0.0053
_CSF_BY = ((34.1, 0.04), (13.5, 0.025))
_CSF_MAX_B = 0.04
_DETECTOR_WIDTH_DEGREES = 0.082
_EPS = 1e-6


def _mul(m, x):
    """3x3 matrix times the channels of [N, 3, H, W]."""
    m = torch.tensor(m, device=x.device, dtype=x.dtype)
    return torch.einsum("ij,njhw->nihw", m, x)


def _white(x):
    return torch.tensor(_WHITE, device=x.device, dtype=x.dtype).view(1, 3, 1, 1)


def rgb_to_ycxcz(rgb):
    xyz = _mul(_RGB_TO_XYZ, rgb) / _white(rgb)
    x, y, z = xyz.unbind(1)
    return torch.stack((116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)), 1)


def ycxcz_to_rgb(ycxcz):
    yy, cx, cz = ycxcz.unbind(1)
    y = (yy + 16.0) / 116.0
    xyz = torch.stack((y + cx / 500.0, y, y - cz / 200.0), 1) * _white(ycxcz)
    return _mul(_XYZ_TO_RGB, xyz)


def hunt_lab(rgb):
    delta = 6.0 / 29.0
    t = _mul(_RGB_TO_XYZ, rgb) / _white(rgb)
    cube = t > delta**3
    f = torch.where(cube, t.clamp_min(delta**3) ** (1.0 / 3.0), t / (3.0 * delta * delta) + 4.0 / 29.0)
    fx, fy, fz = f.unbind(1)
    lightness = 116.0 * fy - 16.0
    hunt = 0.01 * lightness
    return torch.stack((lightness, hunt * 500.0 * (fx - fy), hunt * 200.0 * (fy - fz)), 1)


def _hyab(p, q):
    d = p - q
    return d[:, 0].abs() + (d[:, 1] ** 2 + d[:, 2] ** 2 + _EPS * _EPS).sqrt()


def _taps(radius, f, device):
    x = torch.arange(-radius, radius + 1, device=device, dtype=torch.float64)
    return f(x)


def _rows(x, kernel):
    """Correlates each row of each channel of [N, C, H, W] with the 1-D `kernel` (odd length),
    replicating the borders."""
    r = kernel.numel() // 2
    k = kernel.to(x.dtype).view(1, 1, 1, -1).expand(x.shape[1], 1, 1, -1)
    return F.conv2d(F.pad(x, (r, r, 0, 0), mode="replicate"), k, groups=x.shape[1])


def _columns(x, kernel):
    """`_rows` along the columns."""
    r = kernel.numel() // 2
    k = kernel.to(x.dtype).view(1, 1, -1, 1).expand(x.shape[1], 1, -1, 1)
    return F.conv2d(F.pad(x, (0, 0, r, r), mode="replicate"), k, groups=x.shape[1])


def _separable(x, rows, columns):
    """`rows` along x, then `columns` along y."""
    return _columns(_rows(x, rows), columns)


class Flip:
    """The filters for one viewing distance, built once; `error_map(test, reference)` per pixel,
    `__call__` the mean per image."""

    def __init__(self, device, pixels_per_degree=PIXELS_PER_DEGREE):
        ppd = pixels_per_degree
        radius = math.ceil(3.0 * math.sqrt(_CSF_MAX_B / (2.0 * math.pi**2)) * ppd)

        def profile(b):
            return _taps(radius, lambda i: torch.exp(-(math.pi**2) * (i / ppd) ** 2 / b), device)

        def normalized(k):
            return k / k.sum()

        self.achromatic = normalized(profile(_CSF_A_B))
        self.red_green = normalized(profile(_CSF_RG_B))
        terms = [(a * math.sqrt(math.pi / b), profile(b)) for a, b in _CSF_BY]
        total = sum(c * k.sum() ** 2 for c, k in terms)
        self.blue_yellow = [k * (c / total).sqrt() for c, k in terms]

        sigma = 0.5 * _DETECTOR_WIDTH_DEGREES * ppd
        feature_radius = math.ceil(3.0 * sigma)

        def gaussian(x):
            return torch.exp(-x * x / (2.0 * sigma * sigma))

        def balanced(k):
            positive = k.clamp_min(0.0).sum()
            negative = -k.clamp_max(0.0).sum()
            return torch.where(k > 0, k / positive, torch.where(k < 0, k / negative, torch.zeros_like(k)))

        self.smooth = normalized(_taps(feature_radius, gaussian, device))
        self.edge = balanced(_taps(feature_radius, lambda x: -x * gaussian(x), device))
        self.point = balanced(_taps(feature_radius, lambda x: (x * x / (sigma * sigma) - 1.0) * gaussian(x), device))
        green = hunt_lab(torch.tensor([0.0, 1.0, 0.0], dtype=torch.float64).view(1, 3, 1, 1))
        blue = hunt_lab(torch.tensor([0.0, 0.0, 1.0], dtype=torch.float64).view(1, 3, 1, 1))
        self.cmax = float((_hyab(green, blue) ** _QC).item())

    def _csf(self, opponent):
        y, cx, cz = opponent[:, 0:1], opponent[:, 1:2], opponent[:, 2:3]
        by0, by1 = self.blue_yellow
        return torch.cat(
            (
                _separable(y, self.achromatic, self.achromatic),
                _separable(cx, self.red_green, self.red_green),
                _separable(cz, by0, by0) + _separable(cz, by1, by1),
            ),
            1,
        )

    def _responses(self, luminance):
        smooth_rows = _rows(luminance, self.smooth)

        def magnitude(profile):
            along_x = _separable(luminance, profile, self.smooth)
            along_y = _columns(smooth_rows, profile)
            return (along_x**2 + along_y**2 + _EPS * _EPS).sqrt()

        return magnitude(self.edge), magnitude(self.point)

    def error_map(self, test, reference):
        """Per-pixel FLIP of `test` against `reference`, linear display light [N, 3, H, W]
        (clamped to [0, 1] here): [N, H, W]."""
        maps = []
        for image in (test, reference):
            opponent = rgb_to_ycxcz(image.float().clamp(0.0, 1.0))
            lab = hunt_lab(ycxcz_to_rgb(self._csf(opponent)).clamp(0.0, 1.0))
            maps.append((lab, self._responses((opponent[:, 0:1] + 16.0) / 116.0)))
        (lab_t, (edge_t, point_t)), (lab_r, (edge_r, point_r)) = maps
        error = (_hyab(lab_r, lab_t) + _EPS) ** _QC
        knee = _PC * self.cmax
        color = torch.where(error < knee, error * _PT / knee, _PT + (error - knee) / (self.cmax - knee) * (1.0 - _PT))
        feature = (torch.maximum((edge_r - edge_t).abs(), (point_r - point_t).abs()) / math.sqrt(2.0) + _EPS).sqrt()
        return color.clamp_min(_EPS) ** (1.0 - feature.squeeze(1))

    def __call__(self, test, reference):
        """Mean FLIP of each image: [N]."""
        return self.error_map(test, reference).mean(dim=(1, 2))
