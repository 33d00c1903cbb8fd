"""Trains the recurrent denoiser on `lucid dataset` output and exports its weights.

    python3 train.py --data DIR --minutes 6 --out weights.safetensors --log train.json [--init W]

`--init` starts from a weights file: one of this format, or one of `lucid-rae-v1`, whose enc0 had 16
inputs (15 features and a zero channel): its first 15 input channels are kept and the new inputs'
weights start at zero (`model.load_weights`), so training starts from what v1 computed.
"""

import argparse
import json
import math
import time

import torch
from safetensors.torch import load_file, save_file

from data import load_split, sample_batch
from model import FORMAT, LAYERS, RecurrentDenoiser, export_tensors, load_weights


def tonemap(x):
    return torch.log1p(x.clamp_min(0.0))


def loss_terms(pred, ref):
    """Spatial L1, gradient L1 and temporal L1 on frame differences (Chaitanya et al. 2017), in
    log space, later frames weighted more (the recurrence has warmed up)."""
    p, r = tonemap(pred), tonemap(ref)
    t = p.shape[1]
    wt = torch.linspace(0.5, 1.5, t, device=p.device).view(1, t, 1, 1, 1)
    spatial = (wt * (p - r).abs()).mean()
    gx = lambda x: x[..., :, 1:] - x[..., :, :-1]  # noqa: E731
    gy = lambda x: x[..., 1:, :] - x[..., :-1, :]  # noqa: E731
    grad = (gx(p) - gx(r)).abs().mean() + (gy(p) - gy(r)).abs().mean()
    temporal = ((p[:, 1:] - p[:, :-1]) - (r[:, 1:] - r[:, :-1])).abs().mean()
    return spatial, grad, temporal


@torch.no_grad()
def validate(model, sequences):
    """Mean relMSE and temporal instability (mean |frame difference| of output minus reference's,
    in log space) over whole validation sequences."""
    model.eval()
    rel, inst = [], []
    for s in sequences:
        rec = s["record"].float().unsqueeze(0)
        ref = s["reference"].float().unsqueeze(0)
        out = model(rec)
        rel.append(((out - ref) ** 2 / (ref**2 + 1e-2)).mean().item())
        p, r = tonemap(out), tonemap(ref)
        inst.append(((p[:, 1:] - p[:, :-1]) - (r[:, 1:] - r[:, :-1])).abs().mean().item())
    model.train()
    return {"relmse": sum(rel) / len(rel), "temporal": sum(inst) / len(inst)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", required=True)
    ap.add_argument("--minutes", type=float, default=6.0)
    ap.add_argument("--batch", type=int, default=8)
    ap.add_argument("--frames", type=int, default=8)
    ap.add_argument("--crop", type=int, default=128)
    ap.add_argument("--lr", type=float, default=2e-3)
    ap.add_argument("--weights", default="0.8,0.1,0.1", help="spatial,gradient,temporal loss weights")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--init", help="start from these weights (a file train.py wrote; v1's enc0 is zero-padded)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--log", required=True)
    args = ap.parse_args()
    torch.manual_seed(args.seed)
    dev = "cuda" if torch.cuda.is_available() else "cpu"
    train = load_split(args.data, "train", dev)
    val = load_split(args.data, "validation", dev)
    model = RecurrentDenoiser().to(dev)
    if args.init:
        load_weights(model, load_file(args.init), grow_input=True)
    opt = torch.optim.Adam(model.parameters(), lr=args.lr)
    ws = [float(v) for v in args.weights.split(",")]
    gen = torch.Generator().manual_seed(args.seed)
    budget = args.minutes * 60.0
    start = time.time()
    history, step = [], 0
    while time.time() - start < budget:
        frac = (time.time() - start) / budget
        for group in opt.param_groups:
            group["lr"] = args.lr * 0.5 * (1.0 + math.cos(math.pi * min(frac, 1.0)))
        rec, ref = sample_batch(train, args.batch, args.frames, args.crop, gen)
        rec, ref = rec.to(dev), ref.to(dev)
        with torch.autocast(device_type="cuda", dtype=torch.bfloat16, enabled=dev == "cuda"):
            out = model(rec)
        terms = loss_terms(out.float(), ref)
        loss = sum(w * t for w, t in zip(ws, terms))
        opt.zero_grad(set_to_none=True)
        loss.backward()
        torch.nn.utils.clip_grad_norm_(model.parameters(), 1.0)
        opt.step()
        step += 1
        if step % 250 == 0:
            entry = {"step": step, "seconds": round(time.time() - start, 1), "loss": loss.item()}
            entry.update(validate(model, val))
            history.append(entry)
            print(json.dumps(entry), flush=True)
    final = validate(model, val)
    meta = {
        "format": FORMAT,
        "layers": json.dumps(LAYERS),
        "steps": str(step),
        "data": args.data,
        "init": args.init or "",
        "validation_relmse": f"{final['relmse']:.5f}",
        "validation_temporal": f"{final['temporal']:.5f}",
    }
    save_file(export_tensors(model), args.out, metadata=meta)
    with open(args.log, "w") as f:
        json.dump({"args": vars(args), "final": final, "steps": step, "history": history}, f, indent=1)
    print(json.dumps({"final": final, "steps": step}))


if __name__ == "__main__":
    main()
