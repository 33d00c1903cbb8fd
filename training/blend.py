"""Blends two weights files of one network tensor by tensor, (1 - t) A + t B (a "model soup",
Wortsman et al. 2022): two fine-tunings from the same start stay near each other, so their blend
is a network between them, and a little of one fine-tuning can carry what it learned into the
other without its losses. The shipped weights since the twentieth session are such a blend
(training/README.md, "Blotches held by a blend").

    python3 blend.py A.safetensors B.safetensors --t 0.1 --out W.safetensors

With `--mix-from-b`, the linear mix's channel of the `out` head (its last but for the a-trous
filter's gate) comes from B whole rather than blended: A may hold the mix only as a start
(`widen_scales.py --linear-mix`) that B trained, and a blend would move B's trained mix back
toward that start.

When B reads extra inputs (`train.py --motion-inputs`, `--noise-inputs`) that A does not, A is
taken as the network that started B: its `enc0` reads them with weights at zero.

The output keeps A's metadata but its validation figures (measured on A alone), and adds `blend`:
both files' names, `t`, and B's training options that differ from A's.
"""

import argparse
import json
from pathlib import Path

import torch
from safetensors import safe_open
from safetensors.torch import load_file, save_file

from kernel_model import LINEAR_MIX_CHANNEL
from model import EXTRA_INPUTS, FEATURES
from train import file_extras, file_linear_mix, file_recurrent

# Metadata measured on one file, which a blend does not inherit.
MEASURED = (
    "validation_relmse",
    "validation_ssim",
    "validation_flip",
    "validation_temporal",
    "validation_blotch",
    "validation_light",
    "watch",
)
# Metadata that describes the network rather than its training, which both files must share.
SHARED = ("format", "decoder", "layers", "atrous_steps")


def metadata(path):
    """The safetensors metadata of the file at `path` ({} if it has none)."""
    with safe_open(path, "pt") as f:
        return dict(f.metadata() or {})


def blend(a, b, t):
    """(1 - t) a + t b of every tensor of two {name: tensor} of the same names and shapes."""
    if a.keys() != b.keys():
        raise ValueError(f"the files hold other tensors: {sorted(a.keys() ^ b.keys())}")
    other = [k for k in a if a[k].shape != b[k].shape]
    if other:
        raise ValueError(f"tensors of other shapes: {other}")
    broken = [k for k in a if not (torch.isfinite(a[k]).all() and torch.isfinite(b[k]).all())]
    if broken:
        raise ValueError(f"non-finite values in {broken}")
    return {k: ((1.0 - t) * a[k] + t * b[k]).contiguous() for k in a}


def with_extra_inputs(tensors, have, want):
    """`tensors` of a network reading the extra inputs `have` as one reading `want` (which holds
    them), the others at zero weight: `enc0`'s columns after the input features, in `want`'s order."""
    w = tensors["enc0.weight"]
    columns, at = [w[:, :FEATURES]], FEATURES
    for name in want:
        n = EXTRA_INPUTS[name]
        if name in have:
            columns.append(w[:, at : at + n])
            at += n
        else:
            columns.append(w.new_zeros(w.shape[0], n, *w.shape[2:]))
    return {**tensors, "enc0.weight": torch.cat(columns + [w[:, at:]], 1)}


def take_mix(tensors, b):
    """`tensors` with the `out` head's linear mix channel replaced by `b`'s."""
    for name in ("out.weight", "out.bias"):
        tensors[name][LINEAR_MIX_CHANNEL] = b[name][LINEAR_MIX_CHANNEL]
    return tensors


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a", help="weights a train.py run wrote")
    ap.add_argument("b", help="weights of the same network")
    ap.add_argument("--t", type=float, required=True, help="B's share, from 0 to 1")
    ap.add_argument("--mix-from-b", action="store_true", help="the linear mix's channel from B, not blended")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    if not 0.0 <= args.t <= 1.0:
        raise SystemExit(f"--t {args.t} is not between 0 and 1")
    meta_a, meta_b = metadata(args.a), metadata(args.b)
    a, b = load_file(args.a), load_file(args.b)
    extras_a, extras_b = file_extras(args.a), file_extras(args.b)
    if extras_a != extras_b and set(extras_a) <= set(extras_b):
        if file_recurrent(args.a) or file_recurrent(args.b):
            raise SystemExit(f"{args.a}, {args.b}: extra inputs beside recurrent state are not blended")
        a = with_extra_inputs(a, extras_a, extras_b)
        inputs_b = {f"{name}_inputs": meta_b[f"{name}_inputs"] for name in extras_b}
        meta_a = {**meta_a, "layers": meta_b.get("layers"), **inputs_b}
    inputs = tuple(f"{name}_inputs" for name in EXTRA_INPUTS)
    differing = [k for k in SHARED + inputs if meta_a.get(k) != meta_b.get(k)]
    if differing:
        raise SystemExit(f"{args.a} and {args.b} differ in {differing}: not one network")
    try:
        tensors = blend(a, b, args.t)
    except ValueError as e:
        raise SystemExit(f"{args.a}, {args.b}: {e}") from None
    if args.mix_from_b:
        if not file_linear_mix(args.b):
            raise SystemExit(f"--mix-from-b: {args.b} has no linear mix (its `out` head, out.weight)")
        tensors = take_mix(tensors, b)
    meta = {k: v for k, v in meta_a.items() if k not in MEASURED}
    b_options = {k: v for k, v in meta_b.items() if k not in MEASURED and k not in SHARED and meta_a.get(k) != v}
    meta["blend"] = json.dumps(
        {"a": Path(args.a).name, "b": Path(args.b).name, "t": args.t, "mix_from_b": args.mix_from_b, "b_options": b_options}
    )
    save_file(tensors, args.out, metadata=meta)
    print(json.dumps({"out": args.out, "t": args.t, "tensors": len(tensors), "b_options": b_options}))


if __name__ == "__main__":
    main()
