#!/usr/bin/env python3
"""The wavefront path tracer against the megakernel, per scene, from `lucid bench` JSON files.

    python3 bench/wavefront_table.py DIR_OR_RESULTS_JSON

Reads `bench/run_gpu.sh`'s `results.json` (or its runs folder of `<algo>_<scene>.json`) and prints
a Markdown table: per scene, the median time to the HDR image of `pt`, `pt-wavefront` and
`pt-wavefront-binned` (those present) with each wavefront's ratio to `pt`, and the wavefront's
kernels' medians (each summed over its bounces), plus which is fastest.
"""
import json
import pathlib
import sys

ALGOS = ["pt", "pt-wavefront", "pt-wavefront-binned"]
KERNELS = ["generate", "extend", "shade", "shadow", "accumulate"]


def load(path):
    path = pathlib.Path(path)
    if path.is_dir():
        return {p.stem: json.loads(p.read_text()) for p in sorted(path.glob("*.json"))}
    return json.loads(path.read_text())


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    runs = load(sys.argv[1])
    by_scene = {}
    for run in runs.values():
        if not isinstance(run, dict) or run.get("algorithm") not in ALGOS:
            continue
        if run.get("denoiser") not in (None, "none") or run.get("dynamic"):
            continue
        by_scene.setdefault(run["scene"], {})[run["algorithm"]] = run
    present = [a for a in ALGOS if any(a in r for r in by_scene.values())]
    device = next((r["device"] for s in by_scene.values() for r in s.values()), "?")
    print(f"Median ms to the HDR image on {device}; wavefront kernels: {', '.join(KERNELS)}")
    print()
    print("| scene | " + " | ".join(present) + " | fastest | wavefront kernels |")
    print("| --- " * (len(present) + 3) + "|")
    for scene, algos in sorted(by_scene.items()):
        base = algos.get("pt", {}).get("image_ms", {}).get("median")
        cells = []
        for a in present:
            ms = algos.get(a, {}).get("image_ms", {}).get("median")
            if ms is None:
                cells.append("-")
            elif a != "pt" and base:
                cells.append(f"{ms:.3f} ({ms / base:.2f}x)")
            else:
                cells.append(f"{ms:.3f}")
        timed = {a: r["image_ms"]["median"] for a, r in algos.items()}
        fastest = min(timed, key=timed.get) if timed else "-"
        wave = algos.get("pt-wavefront", {}).get("passes_ms", {})
        kernels = " / ".join(
            f"{wave[f'wavefront.{k}']['median']:.3f}" for k in KERNELS if f"wavefront.{k}" in wave
        )
        print(f"| {scene} | " + " | ".join(cells) + f" | {fastest} | {kernels or '-'} |")


if __name__ == "__main__":
    main()
