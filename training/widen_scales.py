"""Widens a kernel-decoder weights file to more kernel scales, as `train.py --init` does (the new
heads fresh, drawn with `--seed`; the formerly coarsest head's new weight `a` of the next scale at
`--a-bias`, by default train.py's NEW_SCALE_BIAS, so that the new scale starts almost unused),
and/or by the linear mix (`--linear-mix BIAS`: `out`'s new channel's bias, its weights drawn with
`--seed` at a tenth of a fresh layer's, so that the mix varies from pixel to pixel), and/or
(either decoder) by the gate of the a-trous filter over the output (`--atrous-steps S1,S2,...`,
`model.atrous`: `out`'s new last channel, its weights drawn the same way and its bias
`--gate-bias`, by default ATROUS_GATE_BIAS; the steps written to the `atrous_steps` metadata), and
writes it with the source's metadata and the new layer list. Made the five-scale parity weights
(`tests/references/neural_five_scales_weights.safetensors`) with `--a-bias 0`, so that the
sixteenth weighs half in its compositing and the parity test sees it:

    python3 widen_scales.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors --scales 5 \\
        --a-bias 0 --out ../tests/references/neural_five_scales_weights.safetensors

and the linear mix's (`tests/references/neural_linear_mix_weights.safetensors`):

    python3 widen_scales.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors --linear-mix 0 \\
        --out ../tests/references/neural_linear_mix_weights.safetensors

and weights with the gate at about one half, varying from pixel to pixel, for a parity fixture:

    python3 widen_scales.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors --atrous-steps 2,4 \\
        --gate-bias 0 --out gated.safetensors
"""

import argparse
import json

import torch
from safetensors import safe_open
from safetensors.torch import save_file

from kernel_model import HEAD_NAMES, LINEAR_MIX_CHANNEL, kernel_layers
from kernel_model import export_tensors as kernel_export_tensors
from model import ATROUS_GATE_BIAS, atrous_steps_of, export_tensors
from train import (
    NEW_SCALE_BIAS,
    build_model,
    file_atrous_steps,
    file_linear_mix,
    file_scales,
    file_widths,
    load_weights,
    named_convs,
)

# The metadata a weights file keeps from its source: what the renderer reads.
KEPT = (
    "format",
    "decoder",
    "model",
    "emission_motion",
    "history_frames",
    "spatial_variance_frames",
    "atrous_steps",
)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("weights")
    ap.add_argument("--scales", type=int, help="kernel scales (default: the file's)")
    ap.add_argument("--linear-mix", type=float, metavar="BIAS", help="add the linear mix, its logit's bias BIAS")
    ap.add_argument("--a-bias", type=float, default=NEW_SCALE_BIAS)
    ap.add_argument(
        "--atrous-steps", default="", help="add the gate of the a-trous filter of these spacings (e.g. 2,4)"
    )
    ap.add_argument("--gate-bias", type=float, default=ATROUS_GATE_BIAS, help="the gate's logit's bias")
    ap.add_argument(
        "--gate-spread",
        type=float,
        default=0.1,
        help="the gate's weights, drawn, times this (0: weights 0, the gate the same everywhere, as "
        "train.py --init starts it: the other half of a blend with a fine-tuning that added it)",
    )
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    with safe_open(args.weights, "pt") as f:
        meta = {k: v for k, v in (f.metadata() or {}).items() if k in KEPT}
    decoder = meta.get("decoder", "direct")
    kernel = decoder == "kernel"
    if not kernel and (args.scales or args.linear_mix is not None):
        raise SystemExit(f"{args.weights} has the direct decoder: --scales and --linear-mix are the kernel decoder's")
    before = file_scales(args.weights) if kernel else 1
    scales = args.scales or before
    if kernel and not before <= scales <= len(HEAD_NAMES):
        raise SystemExit(f"{args.weights} has {before} scales: --scales takes {before} to {len(HEAD_NAMES)}")
    had_mix = kernel and file_linear_mix(args.weights)
    if had_mix and args.linear_mix is not None:
        raise SystemExit(f"{args.weights} has the linear mix already")
    try:
        new_steps = atrous_steps_of(args.atrous_steps)
    except ValueError as e:
        raise SystemExit(f"--atrous-steps: {e}") from None
    had_steps = file_atrous_steps(args.weights)
    if had_steps and new_steps:
        raise SystemExit(f"{args.weights} has the gate already (atrous_steps {meta['atrous_steps']})")
    if scales == before and args.linear_mix is None and not new_steps:
        raise SystemExit("nothing to widen: give --scales above the file's, --linear-mix or --atrous-steps")
    torch.manual_seed(args.seed)
    linear_mix = had_mix or args.linear_mix is not None
    model = build_model(decoder, file_widths(args.weights), scales, linear_mix, had_steps or new_steps)
    out = named_convs(model)["out"]
    fresh_out = out.weight.detach().clone()
    load_weights(model, args.weights)
    with torch.no_grad():
        if kernel:
            for name in HEAD_NAMES[before - 1 : scales - 1]:
                model.convs["out"].heads[name].bias[-1] = args.a_bias
        if args.linear_mix is not None:
            out.weight[LINEAR_MIX_CHANNEL] = 0.1 * fresh_out[LINEAR_MIX_CHANNEL]
            out.bias[LINEAR_MIX_CHANNEL] = args.linear_mix
        if new_steps:
            out.weight[-1] = args.gate_spread * fresh_out[-1]
            out.bias[-1] = args.gate_bias
            meta["atrous_steps"] = ",".join(str(s) for s in new_steps)
    if kernel:
        layers, tensors = kernel_layers(model.widths, scales, linear_mix, model.gate), kernel_export_tensors(model)
    else:
        layers, tensors = model.layers, export_tensors(model)
    meta["layers"] = json.dumps(layers)
    widened = {"from": args.weights, "scales": scales, "a_bias": args.a_bias, "linear_mix": args.linear_mix}
    if new_steps:
        widened.update(atrous_steps=meta["atrous_steps"], gate_bias=args.gate_bias, gate_spread=args.gate_spread)
    meta["widened"] = json.dumps(widened)
    save_file(tensors, args.out, metadata=meta)
    steps = ",".join(str(s) for s in model.atrous_steps) or "none"
    print(f"{args.out}: {before} -> {scales} scales, linear mix {linear_mix}, a-trous steps {steps}")


if __name__ == "__main__":
    main()
