"""Where a method's error grows or shrinks along a camera path: per-pixel FLIP (as `lucid
evaluate` computes it, `flip.py`) averaged over an early and a late window of a `lucid sequence`
folder's frames, per method, split by what the reference shows there.

    python3 error_growth.py /tmp/heldout-caustics --early 2 5 --late 12 30 --out /tmp/growth

Writes OUT/growth.json: per method, the mean FLIP of each window and its change, split
- by the reference's brightness (bands of its mean luminance, as `lucid evaluate --maps`),
- by how noisy the path tracer's samples are there (the `none` frames' mean absolute deviation
  from the reference's luminance over the late window, relative to it: none, then quartiles),
- by the method's bias there (its late-window mean luminance over the reference's: too dark,
  within 5%, too bright),
and, per frame from the first window's start to the last's end, on the reference's ordinary lit
pixels (0.5-2x its mean luminance): the light the method keeps, its luminance's relative squared
error at the pixel and over 4x4 and 16x16 blocks (the error's scale), and its error's correlation
with the frame before (how long it persists); and OUT/<method>.png, three panels side by side at
a quarter of the resolution: the early window's FLIP, the late window's, and late minus early
(red where it grew, blue where it fell), each on one scale for every method.
"""

import argparse
import json
import struct
import zlib
from pathlib import Path

import numpy as np
import torch

import cold_filter_study
import model
from flip import Flip
from losses import display_linear

BRIGHTNESS_EDGES = (0.1, 0.5, 2.0, 8.0)


def read(path, device):
    """The RGB channels of an EXR frame Lucid wrote, [1, 3, H, W] float32 on `device`."""
    return cold_filter_study.read(path).float().unsqueeze(0).to(device)


def luminance(x):
    """Rec. 709 luminance of [1, 3, H, W] -> [H, W] (`model.luminance`)."""
    return model.luminance(x)[0, 0]


def window_means(test_frames, frames, flip, reference):
    """A method's per-pixel FLIP and luminance averaged over `frames` (of `test_frames`, frame
    index -> image) [H, W] each."""
    error, light = None, None
    for i in frames:
        test = test_frames[i]
        e = flip.error_map(display_linear(test), display_linear(reference[i]))[0].float()
        error = e if error is None else error + e
        lum = luminance(test)
        light = lum if light is None else light + lum
    return error / len(frames), light / len(frames)


def class_figures(e_err, l_err, classes, names):
    """Per class (a boolean mask [H, W]): its share of the pixels, its mean FLIP in each window,
    and its share of the whole image's change of FLIP."""
    total = float((l_err - e_err).mean())
    figures = {}
    for name, mask in zip(names, classes):
        pixels = float(mask.float().mean())
        if not mask.any():
            figures[name] = {"pixels": 0.0}
            continue
        change = float((l_err - e_err)[mask].mean())
        figures[name] = {
            "pixels": pixels,
            "early": float(e_err[mask].mean()),
            "late": float(l_err[mask].mean()),
            "change_share": change * pixels / total if total else 0.0,
        }
    return figures


def brightness_classes(reference_light):
    """Bands of the reference's luminance relative to its mean, as `lucid evaluate --maps`."""
    relative = reference_light / reference_light.mean().clamp_min(1e-12)
    edges = (0.0,) + BRIGHTNESS_EDGES + (float("inf"),)
    names = [f"{lo}-{hi}x" for lo, hi in zip(edges[:-1], edges[1:])]
    return [(relative >= lo) & (relative < hi) for lo, hi in zip(edges[:-1], edges[1:])], names


def quartile_classes(values, label):
    """Pixels where `values` [H, W] is 0 (no noise: sky, black), and quartiles of the others."""
    positive = values > 0
    sample = values[positive][:: max(1, int(positive.sum()) // 1_000_000)]
    q = torch.quantile(sample, torch.tensor([0.25, 0.5, 0.75], device=values.device)).tolist() if sample.numel() else [0.0] * 3
    edges = [0.0, *q, float("inf")]
    classes = [~positive] + [positive & (values > lo) & (values <= hi) for lo, hi in zip(edges[:-1], edges[1:])]
    return classes, [f"no {label}"] + [f"{label} quartile {k + 1}" for k in range(4)]


def bias_classes(light, reference_light):
    """Where the method's mean is too dark, within 5% of the reference's, or too bright."""
    ratio = light / reference_light.clamp_min(1e-6)
    return [ratio < 0.95, (ratio >= 0.95) & (ratio <= 1.05), ratio > 1.05], ["darker", "within 5%", "brighter"]


def viridis_like(x):
    """[H, W] in [0, 1] to an RGB uint8 image [H, W, 3] (black - blue - green - yellow)."""
    stops = np.array([[0, 0, 0], [40, 60, 160], [30, 170, 120], [250, 230, 40]], dtype=np.float64)
    t = np.clip(x, 0.0, 1.0) * (len(stops) - 1)
    i = np.minimum(t.astype(int), len(stops) - 2)
    f = (t - i)[..., None]
    return (stops[i] * (1 - f) + stops[i + 1] * f).astype(np.uint8)


def diverging(x):
    """[H, W] in [-1, 1] to RGB uint8: blue below 0, black at 0, red above."""
    x = np.clip(x, -1.0, 1.0)
    rgb = np.zeros(x.shape + (3,))
    rgb[..., 0] = np.clip(x, 0, 1) * 255
    rgb[..., 2] = np.clip(-x, 0, 1) * 255
    return rgb.astype(np.uint8)


def write_png(path, rgb):
    """Writes an RGB uint8 image [H, W, 3] as a PNG."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    Path(path).write_bytes(png)


def pooled(x, k):
    """[H, W] averaged over k x k blocks."""
    h, w = x.shape[0] // k * k, x.shape[1] // k * k
    return x[:h, :w].reshape(h // k, k, w // k, k).mean(dim=(1, 3))


def frame_series(test_frames, frames, reference):
    """Per frame, on the reference's ordinary lit pixels (0.5-2x its mean luminance): the light the
    method keeps (its luminance summed over the reference's), the relative squared error of the
    luminance at the pixel and averaged over 4x4 and 16x16 blocks (blocks wholly of such pixels),
    which says at what scale the error lies, and the correlation of the luminance error with the same
    pixels' error in the frame before (how long it persists; the per-frame filter's is the
    control: the content and its own bias)."""
    rows, previous = [], None
    for i in frames:
        ref = luminance(reference[i])
        out = luminance(test_frames[i])
        relative = ref / ref.mean().clamp_min(1e-12)
        lit = (relative >= 0.5) & (relative < 2.0)
        row = {"frame": i, "light": float(out[lit].sum() / ref[lit].sum().clamp_min(1e-12))}
        for k in (1, 4, 16):
            o, r, m = pooled(out, k), pooled(ref, k), pooled(lit.float(), k) >= 1.0 - 1e-6
            row[f"rel_mse_{k}"] = float((((o - r) ** 2) / (r * r + 1e-2))[m].mean()) if m.any() else 0.0
        error = out - ref
        if previous is not None:
            both = lit & previous[1]
            a, b = error[both], previous[0][both]
            a, b = a - a.mean(), b - b.mean()
            row["persistence"] = float((a * b).sum() / ((a * a).sum() * (b * b).sum()).sqrt().clamp_min(1e-12))
        previous = (error, lit)
        rows.append(row)
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("folder", help="a `lucid sequence` folder (reference/, none/ and the methods' frames)")
    ap.add_argument("--methods", nargs="+", default=["neural", "svgf", "spatial"])
    ap.add_argument("--early", nargs=2, type=int, default=[2, 5], metavar=("FROM", "TO"), help="frames FROM..TO-1")
    ap.add_argument("--late", nargs=2, type=int, default=[12, 30], metavar=("FROM", "TO"), help="frames FROM..TO-1")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    device = "cuda" if torch.cuda.is_available() else "cpu"
    folder, out = Path(args.folder), Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    early, late = range(*args.early), range(*args.late)
    needed = list(range(min(early.start, late.start), max(early.stop, late.stop)))
    reference = {i: read(folder / "reference" / f"{i:04d}.exr", device) for i in needed}
    flip = Flip(device)
    reference_light = sum(luminance(reference[i]) for i in late) / len(late)
    # How noisy one sample is at each pixel: the 1-sample frames' mean absolute deviation from the
    # reference, relative to it, over the late window.
    noise = sum((luminance(read(folder / "none" / f"{i:04d}.exr", device)) - luminance(reference[i])).abs() for i in late)
    noise = noise / len(late) / reference_light.clamp_min(1e-6)
    shared = [brightness_classes(reference_light), quartile_classes(noise, "sample noise")]
    report = {"folder": str(folder), "early": list(early), "late": list(late), "methods": {}}
    maps = {}
    for method in args.methods:
        test_frames = {i: read(folder / method / f"{i:04d}.exr", device) for i in needed}
        e_err, _ = window_means(test_frames, early, flip, reference)
        l_err, l_light = window_means(test_frames, late, flip, reference)
        change = l_err - e_err
        entry = {"early": float(e_err.mean()), "late": float(l_err.mean()), "change": float(change.mean())}
        for (classes, names), label in zip(shared + [bias_classes(l_light, reference_light)], ("brightness", "noise", "bias")):
            entry[label] = class_figures(e_err, l_err, classes, names)
        entry["per_frame"] = frame_series(test_frames, needed, reference)
        report["methods"][method] = entry
        maps[method] = tuple(pooled(x, 4).cpu().numpy() for x in (e_err, l_err, change))
        print(f"{method}: FLIP {entry['early']:.5f} (frames {args.early[0]}-{args.early[1] - 1}) -> {entry['late']:.5f}", flush=True)
    top = max(np.quantile(np.concatenate([m[1].ravel() for m in maps.values()]), 0.995), 1e-6)
    span = max(np.quantile(np.abs(np.concatenate([m[2].ravel() for m in maps.values()])), 0.995), 1e-6)
    for method, (e, l, c) in maps.items():
        gap = np.full((e.shape[0], 4, 3), 255, dtype=np.uint8)
        panel = np.concatenate([viridis_like(e / top), gap, viridis_like(l / top), gap, diverging(c / span)], axis=1)
        write_png(out / f"{method}.png", panel)
    report["scales"] = {"flip_top": float(top), "change_span": float(span)}
    (out / "growth.json").write_text(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()
