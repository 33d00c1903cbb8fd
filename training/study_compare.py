"""Weights files side by side on the sequences of a dataset's `study` split (`lucid dataset
--scenes`, e.g. the held-out scenes, which training never reads), in PyTorch: for networks the
shaders do not run yet (e.g. `train.py --recurrent`), or to compare without the renderer:

    lucid dataset --scenes classroom,caustics --size 512x512 --frames 30 --sequences 3 \\
        --reference-spp 1024 --out /tmp/study
    python3 study_compare.py --data /tmp/study A.safetensors B.safetensors --out study.json

`--split validation` compares them on a training dataset's validation rooms instead, each and
`all` together. Per file and scene, `train.validate`'s figures over the scene's sequences from no
history (relMSE, SSIM, FLIP, temporal instability, blotches, light kept), and their ratios to the
first file's.
The camera paths are the dataset's (random starts and speeds), not `lucid sequence`'s.
"""

import argparse
import json
from pathlib import Path

import torch
from safetensors import safe_open

from data import load_split
from train import build_model_for, load_weights, validate


def decoder_of(path):
    """The decoder a weights file names (its `decoder` metadata; `direct` where it has none)."""
    with safe_open(path, "pt") as f:
        return (f.metadata() or {}).get("decoder", "direct")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", required=True, help="a dataset with the split compared (`study`: lucid dataset --scenes)")
    ap.add_argument(
        "--split",
        default="study",
        choices=("study", "validation"),
        help="the split compared: `study` (default) or a training dataset's `validation`",
    )
    ap.add_argument("weights", nargs="+", help="weights files train.py wrote; the first is the baseline")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    device = "cuda" if torch.cuda.is_available() else "cpu"
    sequences = load_split(args.data, args.split, device)
    scenes = sorted({s["scene"] for s in sequences})
    results = {}
    for path in args.weights:
        model = build_model_for(decoder_of(path), path).to(device)
        load_weights(model, path)
        results[Path(path).name] = {
            scene: validate(model, [s for s in sequences if s["scene"] == scene]) for scene in scenes
        }
        if args.split == "validation":
            results[Path(path).name]["all"] = validate(model, sequences)
    baseline = results[Path(args.weights[0]).name]
    for name, by_scene in results.items():
        for scene, figures in by_scene.items():
            figures["ratios"] = {k: v / baseline[scene][k] for k, v in figures.items() if baseline[scene][k]}
            print(f"{name} {scene}: " + ", ".join(f"{k} {v:.5f}" for k, v in figures.items() if k != "ratios"))
    counts = {scene: sum(s["scene"] == scene for s in sequences) for scene in scenes}
    summary = {"data": args.data, "split": args.split, "sequences": counts}
    Path(args.out).write_text(json.dumps({**summary, "weights": results}, indent=1))


if __name__ == "__main__":
    main()
