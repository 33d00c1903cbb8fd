#!/usr/bin/env python3
"""Makes the image pairs and reference metric values `tests/tests/metrics_reference.rs` checks
Lucid's FLIP and SSIM against (committed; rerun only to change the set):

    pip install flip-evaluator scikit-image numpy
    python3 tests/metrics_reference/make_reference.py

Writes `pairs/<name>_{reference,test}.f32` (linear RGB, 32-bit little-endian floats, row-major from
the top row, `width` x `height` from `reference.json`) and `reference.json`.

- FLIP: NVIDIA's `flip_evaluator` (the FLIP authors' package). LDR pairs: LDR-FLIP of the linear
  images as they are (`inputsRGB=False`), the default 67.02 pixels per degree (a 0.7 m wide
  3840-pixel monitor at 0.7 m). HDR pairs: HDR-FLIP with its default exposure range (computed
  from the reference) and ACES tone mapper.
- SSIM: scikit-image's `structural_similarity` on what Lucid's `SsimMode::Luminance` compares: the
  Rec.709 luminance (0.2126 R + 0.7152 G + 0.0722 B) of the R, G, B values clamped to [0, 1], with
  `gaussian_weights=True, sigma=1.5` (an 11-tap window: truncate 3.5), `use_sample_covariance=False`,
  `data_range=1.0`, K1 = 0.01, K2 = 0.03 (its defaults), and its mean over the pixels at least 5
  from the border (whose windows lie inside the image). LDR pairs only: SSIM of HDR frames is taken
  of their display images, which are LDR.
"""

import json
import pathlib

import flip_evaluator as flip
import numpy as np
from skimage.metrics import structural_similarity

HERE = pathlib.Path(__file__).resolve().parent
SIZE = (40, 48)  # height, width
REC709 = np.array([0.2126, 0.7152, 0.0722])


def scene(rng):
    """A small synthetic image: a colour gradient, a disc, a bar and a checker patch."""
    h, w = SIZE
    y, x = np.mgrid[0:h, 0:w].astype(np.float64)
    img = np.stack([x / w, y / h, 0.5 + 0.4 * np.sin(x / 5.0)], axis=-1) * 0.8 + 0.1
    disc = (x - 30) ** 2 + (y - 14) ** 2 < 60
    img[disc] = [0.9, 0.2, 0.1]
    img[26:32, 4:40] = [0.05, 0.3, 0.8]
    checker = ((x // 3 + y // 3) % 2 == 0) & (x < 14) & (y < 14)
    img[checker] = [0.95, 0.95, 0.9]
    return np.clip(img + rng.normal(0, 0.01, img.shape), 0, 1)


def box_blur(img, r):
    out = np.zeros_like(img)
    pad = np.pad(img, ((r, r), (r, r), (0, 0)), mode="edge")
    n = 2 * r + 1
    for dy in range(n):
        for dx in range(n):
            out += pad[dy : dy + img.shape[0], dx : dx + img.shape[1]]
    return out / (n * n)


def ldr_pairs(rng):
    ref = scene(rng)
    h, w = SIZE
    yield "ldr_noise", ref, np.clip(ref + rng.normal(0, 0.08, ref.shape), 0, 1)
    yield "ldr_blur", ref, box_blur(ref, 2)
    yield "ldr_hue", ref, ref[..., [1, 2, 0]] * 0.9 + 0.05
    yield "ldr_shift", ref, np.roll(ref, 2, axis=1)
    yield "ldr_dark", ref, ref * 0.6
    sparse = ref.copy()
    sparse[rng.random((h, w)) < 0.03] = 1.0
    yield "ldr_fireflies", ref, sparse
    yield "ldr_identical", ref, ref.copy()


def hdr_pairs(rng):
    base = scene(rng)
    ref = base ** 2.2 * 4.0
    ref[10:16, 30:36] = 40.0  # a lamp
    noisy = ref * rng.gamma(4.0, 0.25, ref.shape)  # unbiased multiplicative noise
    yield "hdr_noise", ref, noisy
    yield "hdr_blur", ref, box_blur(ref, 1)
    yield "hdr_bright", ref, ref * 1.5


def luminance(img):
    return np.clip(img, 0, 1) @ REC709


def ssim(ref, test):
    return structural_similarity(
        luminance(test),
        luminance(ref),
        gaussian_weights=True,
        sigma=1.5,
        use_sample_covariance=False,
        data_range=1.0,
    )


def write(name, ref, test):
    folder = HERE / "pairs"
    folder.mkdir(exist_ok=True)
    for kind, img in (("reference", ref), ("test", test)):
        (folder / f"{name}_{kind}.f32").write_bytes(img.astype("<f4").tobytes())


def main():
    rng = np.random.default_rng(13)
    entries = []
    for name, ref, test in ldr_pairs(rng):
        ref, test = ref.astype(np.float32), test.astype(np.float32)
        write(name, ref, test)
        _, mean, params = flip.evaluate(ref, test, "LDR", inputsRGB=False, applyMagma=False)
        entries.append(
            {
                "name": name,
                "range": "ldr",
                "flip": float(mean),
                "ppd": float(params["ppd"]),
                "ssim": float(ssim(ref.astype(np.float64), test.astype(np.float64))),
            }
        )
    for name, ref, test in hdr_pairs(rng):
        ref, test = ref.astype(np.float32), test.astype(np.float32)
        write(name, ref, test)
        _, mean, params = flip.evaluate(ref, test, "HDR", inputsRGB=False, applyMagma=False)
        entries.append(
            {
                "name": name,
                "range": "hdr",
                "flip": float(mean),
                "ppd": float(params["ppd"]),
                "start_exposure": float(params["startExposure"]),
                "stop_exposure": float(params["stopExposure"]),
                "exposures": int(params["numExposures"]),
                "tonemapper": params["tonemapper"],
            }
        )
    meta = {
        "width": SIZE[1],
        "height": SIZE[0],
        "flip_evaluator": flip.__version__ if hasattr(flip, "__version__") else "1.7",
        "skimage": __import__("skimage").__version__,
        "pairs": entries,
    }
    (HERE / "reference.json").write_text(json.dumps(meta, indent=2) + "\n")


if __name__ == "__main__":
    main()
