"""How the first hits' albedo and emission that re-modulate the learned denoiser's output should be
averaged over time (`model.antialias_surface`): runs the committed weights over the `study`
sequences of a dataset (`lucid dataset --scenes ...`, e.g. the held-out scenes) once per way and
reports relMSE, SSIM (as `lucid evaluate` computes them) and temporal instability (`lucid
evaluate`'s: |frame difference of the output's luminance minus the reference's| over the
reference's mean luminance), per sequence and their means.

    lucid dataset --scenes classroom,caustics --size 960x544 --frames 20 --sequences 2 \\
        --reference-spp 256 --seed 3 --out /tmp/study
    python3 surface_study.py --data /tmp/study --out surface_study.json

Ways (each returns what `antialias_surface` returns: albedo and log(1 + emission)):
`per-frame` (this frame's, as lucid-rae-v3 shipped), `albedo` (only the albedo averaged), and the
albedo with the emission averaged `linear` or as its `log`, each also `-clamped` to the range of
this frame's over the 3x3 neighbourhood, and `shipped` (model.py's: log, clamped, this frame's
weight at least the motion in pixels).
"""

import argparse
import json

import torch

import model
from data import load_split
from losses import display_ssim
from train import build_model_for, load_weights


def averaged(rec, warped, n, mask):
    """The albedo averaged as model.py averages it."""
    alpha = torch.clamp(1.0 / n, min=model.SURFACE_ALPHA)
    return torch.where(mask > 0.0, warped + (rec["albedo"] - warped) * alpha, rec["albedo"])


def emission_way(space, clamped):
    """A way that averages the emission in `space` ("linear" or "log"), optionally clamped."""

    def way(rec, warped_albedo, warped_emission, n, mask, _emission_motion=None):
        alpha = torch.clamp(1.0 / n, min=model.SURFACE_ALPHA)
        value = torch.log1p(rec["emission"])
        prev = warped_emission
        if space == "linear":
            value, prev = rec["emission"], torch.expm1(warped_emission)
        if clamped:
            low, high = model.neighbourhood_range(value)
            prev = torch.minimum(torch.maximum(prev, low), high)
        emission = torch.where(mask > 0.0, prev + (value - prev) * alpha, value)
        if space == "linear":
            emission = torch.log1p(emission)
        return averaged(rec, warped_albedo, n, mask), emission

    return way


WAYS = {
    "per-frame": lambda rec, wa, we, n, mask, _=None: (rec["albedo"], torch.log1p(rec["emission"])),
    "albedo": lambda rec, wa, we, n, mask, _=None: (averaged(rec, wa, n, mask), torch.log1p(rec["emission"])),
    "linear": emission_way("linear", False),
    "linear-clamped": emission_way("linear", True),
    "log": emission_way("log", False),
    "log-clamped": emission_way("log", True),
    "shipped": model.antialias_surface,
}


def temporal_instability(out, ref):
    """`lucid evaluate`'s temporal instability of [1,T,3,H,W] sequences."""
    lum = lambda x: x[:, :, 0] * 0.2126 + x[:, :, 1] * 0.7152 + x[:, :, 2] * 0.0722  # noqa: E731
    lo, lr = lum(out), lum(ref)
    diff = ((lo[:, 1:] - lo[:, :-1]) - (lr[:, 1:] - lr[:, :-1])).abs().mean(dim=(2, 3))
    return (diff.mean() / lr.mean()).item()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", required=True)
    ap.add_argument("--weights", default="../passes/src/denoise/neural/lucid-rae-v3.safetensors")
    ap.add_argument("--decoder", default="kernel")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    dev = "cuda" if torch.cuda.is_available() else "cpu"
    sequences = load_split(args.data, "study", dev)
    net = build_model_for(args.decoder, args.weights).to(dev)
    load_weights(net, args.weights)
    shipped = model.antialias_surface
    results = {}
    try:
        for name, way in WAYS.items():
            model.antialias_surface = way
            rows = []
            with torch.no_grad():
                for s in sequences:
                    rec = s["record"].float().unsqueeze(0)
                    ref = s["reference"].float().unsqueeze(0)
                    out = net(rec, objects=s["objects"].unsqueeze(0))
                    rows.append({
                        "sequence": s["name"],
                        "relmse": ((out - ref) ** 2 / (ref**2 + 1e-2)).mean().item(),
                        "ssim": display_ssim(out[0], ref[0]).mean().item(),
                        "temporal_instability": temporal_instability(out, ref),
                    })
            mean = {k: sum(r[k] for r in rows) / len(rows) for k in ("relmse", "ssim", "temporal_instability")}
            results[name] = {"mean": mean, "sequences": rows}
            print(name, {k: round(v, 4) for k, v in mean.items()}, flush=True)
    finally:
        model.antialias_surface = shipped
    motion = [s["record"][:, 14:16].float().norm(dim=1).median().item() for s in sequences]
    summary = {"data": args.data, "weights": args.weights, "median_motion_px": motion, "ways": results}
    with open(args.out, "w") as f:
        json.dump(summary, f, indent=1)


if __name__ == "__main__":
    main()
