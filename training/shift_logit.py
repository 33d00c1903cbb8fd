"""Copies a kernel-decoder weights file with a constant added to the bias of one of its full
resolution head's logits, every other tensor unchanged: how far the held-out scenes would move
if the network leaned further one way everywhere, without training it again (a probe):

    python3 shift_logit.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors blend 0.7 \\
        --out w-blend+0.7.safetensors

`blend` is the weight of the warped history, b = mask * sigmoid(logit) (`model.py`, `step`);
`gate` the gated a-trous filter's share (a file with `atrous_steps` metadata); `composite` the
weight `a` with which the half scale replaces the full one's low frequencies (`kernel_model.py`).
The metadata gains `shift` (what was added) beside the source file's.
"""

import argparse

from safetensors import safe_open
from safetensors.torch import save_file

from kernel_model import TAPS

# The full resolution head's channels after its TAPS kernel logits.
COMPOSITE = TAPS
BLEND = TAPS + 1


def channel(role, out_channels, meta):
    """The index in `out` of the logit named `role`, for a file with `meta`."""
    if role == "composite":
        return COMPOSITE
    if role == "blend":
        return BLEND
    if not meta.get("atrous_steps"):
        raise SystemExit("the file has no gate (no atrous_steps metadata)")
    return out_channels - 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("weights")
    ap.add_argument("role", choices=["blend", "gate", "composite"])
    ap.add_argument("shift", type=float)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    with safe_open(args.weights, "pt") as f:
        meta = dict(f.metadata() or {})
        tensors = {name: f.get_tensor(name) for name in f.keys()}
    if meta.get("decoder") != "kernel":
        raise SystemExit(f"{args.weights}: not a kernel decoder's weights")
    bias = tensors["out.bias"].clone()
    k = channel(args.role, bias.shape[0], meta)
    bias[k] += args.shift
    tensors["out.bias"] = bias
    meta["shift"] = f"{args.role} logit (out.bias[{k}]) {args.shift:+g}"
    save_file(tensors, args.out, metadata=meta)
    print(f"{args.out}: {args.weights} with out.bias[{k}] ({args.role}) {args.shift:+g}")


if __name__ == "__main__":
    main()
