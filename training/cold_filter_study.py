"""Does the learned denoiser under-filter the first frames after a reset? A study on a folder that
`lucid sequence` wrote (its `neural/`, `albedo/` and `normal/` frames, and `reference/`):

    python3 cold_filter_study.py DIR [--oracle B] STEPS:SIGMA:K [STEPS:SIGMA:K ...]

For each configuration, writes `DIR/neural-cold-<STEPS>-<SIGMA>-<K>/`: the learned denoiser's
frames, each of the first K blended with itself filtered further, by weight 1 - i/K at frame i
(the later frames are links to the learned denoiser's). The filter runs a-trous steps (STEPS,
comma-separated spacings in pixels, e.g. 4,8) of the 5x5 B-spline kernel over the output's
illumination (the output divided by the frame's albedo), each tap weighed by the normals'
agreement (dot product to the 128th power, as SVGF's) and by the illumination's luminance
agreement, exp(-|l_q - l_p| / (SIGMA l_p)); the result is multiplied by the albedo again (pixels
without albedo, the sky, stay as they were). With `--oracle B`, also
`DIR/neural-oracle-<STEPS>-<SIGMA>-<K>/`: per B x B block of each frame, whichever of the two
images is closer to the reference in tone-mapped luminance (x / (1 + x), x the luminance over the
reference's mean), the bound of a choice of where to filter learned at that coarseness. `lucid
evaluate DIR` then scores the new folders beside the others (they are named `neural-*`). Runs on
the GPU when torch has one.
"""

import argparse
import shutil
from pathlib import Path

import numpy as np
import OpenEXR
import torch
import torch.nn.functional as F

B_SPLINE = (1 / 16, 1 / 4, 3 / 8, 1 / 4, 1 / 16)
LUMINANCE = (0.2126, 0.7152, 0.0722)


def read(path):
    """The RGB channels of an EXR image that Lucid wrote, as a 3 x H x W float64 tensor."""
    with OpenEXR.File(str(path)) as f:
        rgba = f.channels()["RGBA"].pixels
    return torch.from_numpy(np.ascontiguousarray(rgba[:, :, :3], dtype=np.float64)).permute(2, 0, 1)


def write(path, rgb):
    """Writes a 3 x H x W tensor as an RGBA EXR image (alpha 1), as Lucid writes its frames."""
    rgb = rgb.permute(1, 2, 0).cpu().numpy()
    rgba = np.concatenate([rgb, np.ones(rgb.shape[:2] + (1,))], axis=2).astype(np.float32)
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    with OpenEXR.File(header, {"RGBA": rgba}) as f:
        f.write(str(path))


def luminance(x):
    """Rec. 709 luminance of a 3 x H x W tensor, 1 x H x W."""
    return sum(w * x[c] for c, w in enumerate(LUMINANCE))[None]


def shifted(x, dy, dx):
    """x moved by (dy, dx) pixels, edges replicated."""
    pad = max(abs(dy), abs(dx))
    padded = F.pad(x[None], (pad, pad, pad, pad), mode="replicate")[0]
    h, w = x.shape[1:]
    return padded[:, pad + dy : pad + dy + h, pad + dx : pad + dx + w]


def atrous(illumination, normal, steps, sigma):
    """The edge-aware a-trous steps over `illumination` (3 x H x W)."""
    x = illumination
    for step in steps:
        centre = luminance(x)
        total = torch.zeros_like(x)
        weights = torch.zeros_like(centre)
        for i, ky in enumerate(B_SPLINE):
            for j, kx in enumerate(B_SPLINE):
                dy, dx = (i - 2) * step, (j - 2) * step
                tap, tap_normal = shifted(x, dy, dx), shifted(normal, dy, dx)
                w_normal = (normal * tap_normal).sum(0, keepdim=True).clamp_min(0.0) ** 128
                w_lum = torch.exp(-(luminance(tap) - centre).abs() / (sigma * centre + 1e-4))
                w = ky * kx * w_normal * w_lum
                total += w * tap
                weights += w
        x = torch.where(weights > 1e-12, total / weights.clamp_min(1e-12), x)
    return x


def block_oracle(neural, filtered, reference, block):
    """Per `block` x `block` block, `filtered` where it is closer to `reference` than `neural` (the
    squared error of their tone-mapped luminance summed over the block), else `neural`; a partial
    block at the right or bottom edge keeps `neural`."""
    mean = luminance(reference).mean()

    def tone(x):
        x = luminance(x) / mean
        return x / (1.0 + x)

    target = tone(reference)
    errors = [F.avg_pool2d(((tone(x) - target) ** 2)[None], block)[0] for x in (neural, filtered)]
    better = (errors[1] < errors[0]).to(neural.dtype)
    h, w = neural.shape[1:]
    choice = better.repeat_interleave(block, 1).repeat_interleave(block, 2)
    choice = F.pad(choice, (0, w - choice.shape[2], 0, h - choice.shape[1]))
    return neural + choice * (filtered - neural)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dir", type=Path)
    ap.add_argument("configs", nargs="+", help="STEPS:SIGMA:K, e.g. 4,8:0.1:2")
    ap.add_argument("--oracle", type=int, metavar="B", help="also the block oracle of each, B x B blocks")
    args = ap.parse_args()
    dev = "cuda" if torch.cuda.is_available() else "cpu"
    frames = sorted(p.name for p in (args.dir / "neural").glob("*.exr"))
    if not frames:
        raise SystemExit(f"{args.dir / 'neural'} holds no frames")
    configs = []
    for text in args.configs:
        try:
            steps, sigma, k = text.split(":")
            configs.append(([int(s) for s in steps.split(",")], float(sigma), int(k)))
        except ValueError:
            raise SystemExit(f"configuration '{text}' is not STEPS:SIGMA:K (e.g. 4,8:0.1:2)") from None
        if configs[-1][2] < 1:
            raise SystemExit(f"configuration '{text}': K is at least 1")

    # Each frame that some configuration filters, read once: (neural, normal, albedo, reference).
    inputs = {}

    def frame_inputs(name):
        if name not in inputs:
            neural, albedo, normal = (read(args.dir / d / name).to(dev) for d in ("neural", "albedo", "normal"))
            normal = normal / normal.norm(dim=0, keepdim=True).clamp_min(1e-6)
            reference = read(args.dir / "reference" / name).to(dev) if args.oracle else None
            inputs[name] = (neural, normal, albedo, reference)
        return inputs[name]

    for steps, sigma, k in configs:
        tag = f"{'_'.join(map(str, steps))}-{sigma}-{k}"
        outs = [args.dir / f"neural-cold-{tag}"] + ([args.dir / f"neural-oracle-{tag}"] if args.oracle else [])
        for out in outs:
            if out.exists():
                shutil.rmtree(out)
            out.mkdir()
        for index, name in enumerate(frames):
            weight = max(0.0, 1.0 - index / k)
            if weight == 0.0:
                for out in outs:
                    (out / name).symlink_to(Path("..") / "neural" / name)
                continue
            neural, normal, albedo, reference = frame_inputs(name)
            lit = albedo.amax(0, keepdim=True) > 1e-3
            safe = albedo.clamp_min(1e-3)
            filtered = atrous(neural / safe, normal, steps, sigma) * safe
            filtered = torch.where(lit, neural + weight * (filtered - neural), neural)
            write(outs[0] / name, filtered)
            if args.oracle:
                write(outs[1] / name, block_oracle(neural, filtered, reference, args.oracle))
        print(f"{outs[0]}: {len(frames)} frames, the first {k} filtered further")


if __name__ == "__main__":
    main()
