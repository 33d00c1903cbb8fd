"""How much of the `caustics` crescent's light a 5x5 box filter keeps when it averages the noisy
input in linear space and in log(1 + x), as the learned denoiser's kernels do, at full resolution
and on the input average-pooled 2x, 4x and 8x (the kernel scales), from crops.npz (job.sh): the
demodulated noisy luminance (noisy over the first hit's albedo) filtered, re-modulated, and averaged
over the crop's pixels where the 1024-sample reference is over 2, against the reference there.
Run: python3 log_domain.py [crops.npz]"""
import sys

import numpy as np
import torch
import torch.nn.functional as F


def luminance(x):
    return 0.2126 * x[..., 0] + 0.7152 * x[..., 1] + 0.0722 * x[..., 2]


def box5(x):
    return F.avg_pool2d(F.pad(x, (2, 2, 2, 2), mode="replicate"), 5, 1)


crops = np.load(sys.argv[1] if len(sys.argv) > 1 else "crops.npz")
for frame in (5, 9):
    reference = luminance(crops[f"reference_{frame}"].astype(np.float32))
    noisy = luminance(np.nan_to_num(crops[f"none_{frame}"].astype(np.float32)))
    albedo = luminance(crops[f"albedo_{frame}"].astype(np.float32)).clip(1e-3)
    bright = reference > 2.0
    demodulated = torch.tensor(noisy / albedo)[None, None]
    row = [f"frame {frame}: {bright.sum()} pixels, noisy {noisy[bright].mean() / reference[bright].mean():.3f}"]
    for scale in (1, 2, 4, 8):
        pooled = F.avg_pool2d(demodulated, scale) if scale > 1 else demodulated
        kept = []
        for filtered in (box5(pooled), torch.expm1(box5(torch.log1p(pooled)))):
            full = F.interpolate(filtered, scale_factor=scale, mode="nearest") if scale > 1 else filtered
            kept.append((full[0, 0].numpy() * albedo)[bright].mean() / reference[bright].mean())
        row.append(f"scale 1/{scale}: linear {kept[0]:.3f}, log {kept[1]:.3f}")
    print("; ".join(row))
