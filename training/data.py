"""Reads what `lucid dataset` writes: `index.json` and one safetensors file per camera-path
sequence, holding `record` [T, RECORD_SIZE, H, W] and `reference` [T, 3, H, W] in float16 and
`objects` [T, H, W] (each pixel's object id, int32; datasets from before it have none: all one
object); or a folder of such datasets (`shard-K/`, as `dataset_gpu.sh` renders them in parallel),
read as one."""

import json
import math
from pathlib import Path

import torch
from safetensors.torch import load_file

from model import LUMINANCE, RECORD_SIZE


def dataset_folders(root):
    """The datasets under `root`: itself when it holds an `index.json`, else its `shard-*` folders."""
    root = Path(root)
    if (root / "index.json").exists():
        return [root]
    shards = sorted(p for p in root.glob("shard-*") if (p / "index.json").exists())
    if not shards:
        raise ValueError(f"{root}: neither an index.json nor shard-*/index.json")
    return shards


def load_split(root, split, device, part=(0, 1), scenes=None):
    """The sequences of `split` ("train", "validation" or "study") as a list of dicts with
    `record`, `reference` (float16 on `device`), `objects` ([T,1,H,W] float32 on `device`, as
    `model.RecurrentDenoiser.step` takes them; zero where the dataset has none), `name` and
    `scene`. `part` = (k, n): only every n-th sequence of the split from the k-th (a data-parallel
    process's share: each loads only its own); `scenes`: only the sequences of these scenes (then
    possibly none: the caller says which scenes it missed)."""
    out = []
    k, n = part
    i = -1
    for folder in dataset_folders(root):
        index = json.loads((folder / "index.json").read_text())
        for entry in index["sequences"]:
            if entry["split"] != split or (scenes is not None and entry.get("scene", "") not in scenes):
                continue
            i += 1
            if i % n != k:
                continue
            tensors = load_file(str(folder / entry["file"]))
            record, reference = tensors["record"], tensors["reference"]
            name = f"{folder.name}/{entry['file']}"
            if record.shape[1] != RECORD_SIZE:
                raise ValueError(f"{name}: record has {record.shape[1]} channels, expected {RECORD_SIZE}")
            for key in ("record", "reference"):
                bad = ~torch.isfinite(tensors[key])
                if bad.any():
                    t, c, y, x = bad.nonzero()[0].tolist()
                    raise ValueError(
                        f"{name}: {key} holds {bad.sum().item()} non-finite values (the first at frame {t}, "
                        f"channel {c}, y {y}, x {x}): render the dataset again with a lucid that saturates them"
                    )
            objects = tensors.get("objects")
            if objects is None:
                objects = torch.zeros(record.shape[0], record.shape[2], record.shape[3], dtype=torch.int32)
            objects = objects.unsqueeze(1).float().to(device)
            out.append(
                {
                    "name": name,
                    "scene": entry.get("scene", ""),
                    "record": record.to(device),
                    "reference": reference.to(device),
                    "objects": objects,
                }
            )
    if not out and scenes is None:
        share = f" in share {k} of {n}" if n > 1 else ""
        raise ValueError(f"{root}: no '{split}' sequences{share}")
    return out


def sample_batch(sequences, batch, frames, crop, generator):
    """`batch` random windows of `frames` consecutive frames, each a random `crop` x `crop` tile of
    one sequence, with a random exposure scale (radiance-like channels scaled together). Returns
    float32 (records [B,T,C,H,W], references [B,T,3,H,W], object ids [B,T,1,H,W])."""
    recs, refs, objs = [], [], []
    for _ in range(batch):
        s = sequences[int(torch.randint(len(sequences), (1,), generator=generator))]
        t_total, _, h, w = s["record"].shape
        t0 = int(torch.randint(t_total - frames + 1, (1,), generator=generator))
        y0 = int(torch.randint((h - crop) // 4 + 1, (1,), generator=generator)) * 4
        x0 = int(torch.randint((w - crop) // 4 + 1, (1,), generator=generator)) * 4
        rec = s["record"][t0 : t0 + frames, :, y0 : y0 + crop, x0 : x0 + crop].float()
        ref = s["reference"][t0 : t0 + frames, :, y0 : y0 + crop, x0 : x0 + crop].float()
        objs.append(s["objects"][t0 : t0 + frames, :, y0 : y0 + crop, x0 : x0 + crop])
        scale = float(torch.exp(torch.empty(1).uniform_(-1.4, 1.4, generator=generator)))
        rec = rec.clone()
        rec[:, 0:3] *= scale  # demodulated
        rec[:, 6:9] *= scale  # emission
        recs.append(rec)
        refs.append(ref * scale)
    return torch.stack(recs), torch.stack(refs), torch.stack(objs)


# How much brighter than its frame's mean an added firefly is: drawn log-uniformly in this range.
FIREFLY_GAIN = (10.0, 1e4)


def add_fireflies(radiance, rate, generator):
    """`radiance` [B,T,3,H,W] (demodulated) with isolated bright samples added at `rate` per pixel
    and frame, each FIREFLY_GAIN times its frame's mean luminance and tinted at random: samples of
    paths so rare that no neighbour and no other frame supports them, which the references lack."""
    b, t, _, h, w = radiance.shape
    draw = lambda *shape: torch.rand(*shape, generator=generator, device=radiance.device)  # noqa: E731
    hit = draw(b, t, 1, h, w) < rate
    lo, hi = (math.log(g) for g in FIREFLY_GAIN)
    gain = torch.exp(lo + (hi - lo) * draw(b, t, 1, h, w))
    weights = torch.tensor(LUMINANCE, device=radiance.device).view(1, 1, 3, 1, 1)
    mean = (radiance * weights).sum(2, keepdim=True).mean((3, 4), keepdim=True).clamp_min(1e-3)
    tint = 0.5 + 0.5 * draw(b, t, 3, h, w)
    return radiance + hit * gain * mean * tint
