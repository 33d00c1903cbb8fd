"""Writes a parity fixture (`tests/references/neural_parity*.safetensors`): consecutive frames (two,
or `--frames` of a dataset's sequence) of per-pixel records and what `model.py` (or
`kernel_model.py`, as the weights' `decoder` metadata says) computes from them with the given weights (half-precision storage emulated; with the weights'
`atrous_steps`, their gated a-trous filter): the denoised radiance (`expected`), the running mean
with its length (`accum`), the second moment of luminance (`moment`) and the range-compressed
running mean with its second moment (`robust`), which `tests/neural_parity.rs` checks the Vulkan
inference against. The synthetic pair also has each pixel's object id (`objects`), as do the
dataset's frames of a dataset that has them.

    python3 make_parity.py --weights ../passes/src/denoise/neural/lucid-rae-v3.safetensors \
        [--data DATASET_DIR | --records FIXTURE] --out ../tests/references/neural_parity.safetensors

With `--data`, the frames are a crop (`--size`, 32x24 by default) of the first validation (or
`--scenes` study) sequence's first two frames, or `--frames` (and their object ids, where the
dataset has them);
with `--records`, the records of an existing fixture (to keep its frames when only the model or
the weights change); without either, a synthetic pair (a textured plane seen by a camera that
moves by a sub-pixel offset, an emitter on it that is an object of its own, sky in a corner, and
an object appearing in the second frame).
Run it again whenever the weights change.
"""

import argparse
import json
from pathlib import Path

import torch
from safetensors.torch import load_file, save_file

from data import dataset_folders
from model import OBJECT_BITS, RECORD_SIZE
from train import build_model_for, load_weights

SIZE = "32x24"


def synthetic(W, H):
    """The synthetic records of `W` x `H` pixels and their object ids ([2,1,H,W], as the shaders
    keep them)."""
    g = torch.Generator().manual_seed(7)
    rec = torch.zeros(2, RECORD_SIZE, H, W)
    objects = torch.zeros(2, 1, H, W)
    ys, xs = torch.meshgrid(torch.arange(H).float(), torch.arange(W).float(), indexing="ij")
    shift = torch.tensor([0.35, -0.6])
    for t in range(2):
        u = xs + t * shift[0]
        v = ys + t * shift[1]
        albedo = torch.stack([0.5 + 0.4 * torch.sin(u * 0.7), 0.5 + 0.4 * torch.cos(v * 0.5), 0.6 + 0.0 * u])
        rec[t, 0:3] = torch.empty(3, H, W).exponential_(1.0, generator=g) * (1.0 + 0.5 * torch.sin(u * 0.2))
        rec[t, 3:6] = albedo
        emitter = (u > 20) & (v < 6)
        rec[t, 6:9] = torch.where(emitter, 4.0, 0.0).expand(3, H, W)
        objects[t, 0] = torch.where(emitter, 1.0, 0.0)
        n = torch.stack([0.1 * torch.sin(u * 0.3), torch.ones_like(u), 0.1 * torch.cos(v * 0.3)])
        rec[t, 9:12] = n / n.norm(dim=0, keepdim=True)
        rec[t, 12] = 0.3 + 0.2 * torch.sin(u * 0.1)
        depth = 3.0 + 0.05 * v
        depth[:3, :5] = 0.0  # sky
        if t == 1:
            depth[12:20, 8:16] = 1.5  # an object that last frame did not see here: disoccluded
            objects[t, 0, 12:20, 8:16] = 2.0
        objects[t, 0, :3, :5] = float(OBJECT_BITS)  # the sky's id
        rec[t, 13] = depth
        rec[t, 14] = -shift[0]
        rec[t, 15] = -shift[1]
        rec[t, 16] = torch.where(depth > 0, depth + 0.01, 0.0)
    # Half floats, as `lucid dataset` stores records (the parity test uploads the half-precision
    # channels into the G-buffer's half-precision images, exactly).
    return rec.half().float(), objects


def from_dataset(root, W, H, frames):
    folder = dataset_folders(root)[0]
    index = json.loads((folder / "index.json").read_text())
    entry = next(e for e in index["sequences"] if e["split"] in ("validation", "study"))
    tensors = load_file(str(folder / entry["file"]))
    rec = tensors["record"][:frames].float()
    _, _, h, w = rec.shape
    y0, x0 = (h - H) // 2 // 4 * 4, (w - W) // 2 // 4 * 4
    crop = rec[:, :, y0 : y0 + H, x0 : x0 + W].contiguous()
    objects = tensors.get("objects")
    if objects is not None:
        objects = objects[:frames, None, y0 : y0 + H, x0 : x0 + W].float().contiguous()
    return crop, objects


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--weights", required=True)
    group = ap.add_mutually_exclusive_group()
    group.add_argument("--data")
    group.add_argument("--records", help="reuse the records of this parity fixture")
    ap.add_argument(
        "--size",
        default=SIZE,
        help="WxH of the synthetic frames or the dataset's crop (a network of N kernel scales needs "
        "sizes divisible by 2^(N-1), as training's crops are)",
    )
    ap.add_argument("--frames", type=int, default=2, help="frames of a dataset's sequence")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    W, H = (int(v) for v in args.size.split("x"))
    decoder = safe_open_metadata(args.weights).get("decoder", "direct")
    model = build_model_for(decoder, args.weights)
    load_weights(model, args.weights)
    objects = None
    if args.data:
        (record, objects), source = from_dataset(args.data, W, H, args.frames), args.data
    elif args.records:
        fixture = load_file(args.records)
        record, objects = fixture["record"], fixture.get("objects")
        source = safe_open_metadata(args.records).get("source", args.records)
    else:
        (record, objects), source = synthetic(W, H), "synthetic"
    expected, accum, moment, robust, state = [], [], [], [], None
    with torch.no_grad():
        for t in range(record.shape[0]):
            frame_objects = None if objects is None else objects[t : t + 1]
            y, state = model.step(record[t : t + 1], state, fp16_storage=True, objects=frame_objects)
            expected.append(y[0])
            accum.append(state["accum"][0])
            moment.append(state["moment"][0])
            robust.append(state["robust"][0])
    tensors = {"record": record, "expected": expected, "accum": accum, "moment": moment, "robust": robust}
    if objects is not None:
        tensors["objects"] = objects
    tensors = {k: (torch.stack(v) if isinstance(v, list) else v).contiguous() for k, v in tensors.items()}
    metadata = {"weights": Path(args.weights).name, "decoder": decoder, "source": source}
    save_file(tensors, args.out, metadata=metadata)
    reprojected = (tensors["accum"][-1, 3] > 1.0).float().mean().item()
    print(f"{args.out}: {record.shape[3]}x{record.shape[2]}, {record.shape[0]} frames, from {source}; running mean reprojected at {reprojected:.0%}")


def safe_open_metadata(path):
    """The metadata of a safetensors file."""
    from safetensors import safe_open

    with safe_open(path, "pt") as f:
        return f.metadata() or {}


if __name__ == "__main__":
    main()
