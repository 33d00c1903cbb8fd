"""Widens a kernel-decoder weights file to more kernel scales, as `train.py --init` does (the new
heads fresh, drawn with `--seed`; the formerly coarsest head's new weight `a` of the next scale at
`--a-bias`, by default train.py's NEW_SCALE_BIAS, so that the new scale starts almost unused),
and writes it with the source's metadata and the new layer list. Made the five-scale parity weights
(`tests/references/neural_five_scales_weights.safetensors`) with `--a-bias 0`, so that the
sixteenth weighs half in its compositing and the parity test sees it:

    python3 widen_scales.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors --scales 5 \\
        --a-bias 0 --out ../tests/references/neural_five_scales_weights.safetensors
"""

import argparse
import json

import torch
from safetensors import safe_open
from safetensors.torch import save_file

from kernel_model import HEAD_NAMES, export_tensors, kernel_layers
from train import NEW_SCALE_BIAS, build_model, file_scales, file_widths, load_weights

# The metadata a weights file keeps from its source: what the renderer reads.
KEPT = ("format", "decoder", "model", "emission_motion")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("weights")
    ap.add_argument("--scales", type=int, required=True)
    ap.add_argument("--a-bias", type=float, default=NEW_SCALE_BIAS)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    before = file_scales(args.weights)
    if not before < args.scales <= len(HEAD_NAMES):
        raise SystemExit(f"{args.weights} has {before} scales: --scales takes {before + 1} to {len(HEAD_NAMES)}")
    torch.manual_seed(args.seed)
    model = build_model("kernel", file_widths(args.weights), args.scales)
    load_weights(model, args.weights)
    heads = model.convs["out"].heads
    with torch.no_grad():
        for name in HEAD_NAMES[before - 1 : args.scales - 1]:
            heads[name].bias[-1] = args.a_bias
    with safe_open(args.weights, "pt") as f:
        meta = {k: v for k, v in (f.metadata() or {}).items() if k in KEPT}
    meta["layers"] = json.dumps(kernel_layers(model.widths, args.scales))
    meta["widened"] = json.dumps({"from": args.weights, "scales": args.scales, "a_bias": args.a_bias})
    save_file(export_tensors(model), args.out, metadata=meta)
    print(f"{args.out}: {before} -> {args.scales} scales")


if __name__ == "__main__":
    main()
