"""Copies a weights file with metadata entries set, its tensors unchanged: a setting the renderer
reads from the file (e.g. `history_frames`, the most frames the running means average) tried on
trained weights without training them again:

    python3 set_metadata.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors \\
        history_frames=12 --out w-h12.safetensors
"""

import argparse

from safetensors import safe_open
from safetensors.torch import save_file


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("weights")
    ap.add_argument("entries", nargs="+", metavar="KEY=VALUE")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    with safe_open(args.weights, "pt") as f:
        meta = dict(f.metadata() or {})
        tensors = {name: f.get_tensor(name) for name in f.keys()}
    for entry in args.entries:
        key, sep, value = entry.partition("=")
        if not sep or not key:
            raise SystemExit(f"{entry!r} is not KEY=VALUE")
        meta[key] = value
    save_file(tensors, args.out, metadata=meta)
    print(f"{args.out}: {args.weights} with {', '.join(args.entries)}")


if __name__ == "__main__":
    main()
