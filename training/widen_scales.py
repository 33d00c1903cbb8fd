"""Widens a kernel-decoder weights file to more kernel scales, as `train.py --init` does (the new
heads fresh, drawn with `--seed`; the formerly coarsest head's new weight `a` of the next scale at
`--a-bias`, by default train.py's NEW_SCALE_BIAS, so that the new scale starts almost unused),
and/or by the linear mix (`--linear-mix BIAS`: `out`'s new channel's bias, its weights drawn with
`--seed` at a tenth of a fresh layer's, so that the mix varies from pixel to pixel), and writes it
with the source's metadata and the new layer list. Made the five-scale parity weights
(`tests/references/neural_five_scales_weights.safetensors`) with `--a-bias 0`, so that the
sixteenth weighs half in its compositing and the parity test sees it:

    python3 widen_scales.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors --scales 5 \\
        --a-bias 0 --out ../tests/references/neural_five_scales_weights.safetensors

and the linear mix's (`tests/references/neural_linear_mix_weights.safetensors`):

    python3 widen_scales.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors --linear-mix 0 \\
        --out ../tests/references/neural_linear_mix_weights.safetensors
"""

import argparse
import json

import torch
from safetensors import safe_open
from safetensors.torch import save_file

from kernel_model import HEAD_NAMES, export_tensors, kernel_layers
from train import NEW_SCALE_BIAS, build_model, file_linear_mix, file_scales, file_widths, load_weights

# The metadata a weights file keeps from its source: what the renderer reads.
KEPT = ("format", "decoder", "model", "emission_motion", "history_frames", "spatial_variance_frames")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("weights")
    ap.add_argument("--scales", type=int, help="kernel scales (default: the file's)")
    ap.add_argument("--linear-mix", type=float, metavar="BIAS", help="add the linear mix, its logit's bias BIAS")
    ap.add_argument("--a-bias", type=float, default=NEW_SCALE_BIAS)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    before = file_scales(args.weights)
    scales = args.scales or before
    if not before <= scales <= len(HEAD_NAMES):
        raise SystemExit(f"{args.weights} has {before} scales: --scales takes {before} to {len(HEAD_NAMES)}")
    had_mix = file_linear_mix(args.weights)
    if had_mix and args.linear_mix is not None:
        raise SystemExit(f"{args.weights} has the linear mix already")
    if scales == before and args.linear_mix is None:
        raise SystemExit("nothing to widen: give --scales above the file's or --linear-mix")
    torch.manual_seed(args.seed)
    linear_mix = had_mix or args.linear_mix is not None
    model = build_model("kernel", file_widths(args.weights), scales, linear_mix)
    fresh_out = model.convs["out"].heads["out"].weight.detach().clone()
    load_weights(model, args.weights)
    heads = model.convs["out"].heads
    with torch.no_grad():
        for name in HEAD_NAMES[before - 1 : scales - 1]:
            heads[name].bias[-1] = args.a_bias
        if args.linear_mix is not None:
            heads["out"].weight[-1] = 0.1 * fresh_out[-1]
            heads["out"].bias[-1] = args.linear_mix
    with safe_open(args.weights, "pt") as f:
        meta = {k: v for k, v in (f.metadata() or {}).items() if k in KEPT}
    meta["layers"] = json.dumps(kernel_layers(model.widths, scales, linear_mix))
    widened = {"from": args.weights, "scales": scales, "a_bias": args.a_bias, "linear_mix": args.linear_mix}
    meta["widened"] = json.dumps(widened)
    save_file(export_tensors(model), args.out, metadata=meta)
    print(f"{args.out}: {before} -> {scales} scales, linear mix {linear_mix}")


if __name__ == "__main__":
    main()
