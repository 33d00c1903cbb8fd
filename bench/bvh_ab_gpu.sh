#!/usr/bin/env bash
# A/B of the GPU BVH layouts (binary vs compressed wide), back to back on the NVIDIA machine:
#   source .gpu/env.sh && LUCID=/tmp/lucid bench/bvh_ab_gpu.sh OUT_DIR
# For each scene (SCENES, default cornell-box cornell-teapot covered-light classroom) and algorithm
# (ALGOS, default "pt bdpt"), runs `lucid bench --bvh binary` and `--bvh wide` one after the other
# at 1920x1080 (SIZE), 1 spp, max depth 8 (FRAMES measured frames after 10 warm-up), ROUNDS times (default
# 2, the order alternating per round so clock drift favours neither), each run's JSON in $RUNS, and
# writes OUT_DIR/bvh_ab.json (every run plus per-configuration medians of the light-transport pass,
# the HDR image and the frame) and prints the comparison.
set -euo pipefail
out=${1:?usage: LUCID=/tmp/lucid bench/bvh_ab_gpu.sh OUT_DIR}
lucid=${LUCID:-/tmp/lucid}
frames=${FRAMES:-100}
size=${SIZE:-1920x1080}
rounds=${ROUNDS:-2}
runs=${RUNS:-/tmp/lucid-bvh-ab-runs}
scenes=${SCENES:-cornell-box cornell-teapot covered-light classroom}
algos=${ALGOS:-pt bdpt}
mkdir -p "$out" "$runs"
"$lucid" info --json > "$runs/info.json"
for round in $(seq 1 "$rounds"); do
  if [ $((round % 2)) = 1 ]; then layouts="binary wide"; else layouts="wide binary"; fi
  for scene in $scenes; do
    for algo in $algos; do
      for bvh in $layouts; do
        "$lucid" bench --scene "$scene" --algo "$algo" --bvh "$bvh" --size "$size" --spp 1 \
          --max-depth 8 --frames "$frames" --warmup 10 --pipeline-statistics \
          --json "$runs/${scene}_${algo}_${bvh}_r${round}.json" > /dev/null
        echo "done round $round $scene $algo $bvh"
      done
    done
  done
done
python3 - "$out" "$runs" <<'PY'
import json, pathlib, statistics, sys
out, runs_dir = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
runs = {p.stem: json.loads(p.read_text()) for p in sorted(runs_dir.glob("*_r*.json"))}
# The light-transport passes: path_trace, or bdpt's camera and light passes.
def transport_ms(r):
    return sum(v["median"] for k, v in r["passes_ms"].items()
               if k.startswith("path_trace") or k.startswith("bdpt"))
groups = {}
for name, r in runs.items():
    key = (r["scene"], r["algorithm"], r["bvh"])
    groups.setdefault(key, []).append(r)
summary = {}
for (scene, algo, bvh), rs in sorted(groups.items()):
    summary[f"{scene}/{algo}/{bvh}"] = {
        "runs": len(rs),
        "transport_ms": statistics.median(transport_ms(r) for r in rs),
        "image_ms": statistics.median(r["image_ms"]["median"] for r in rs),
        "frame_ms": statistics.median(r["frame_ms"]["median"] for r in rs),
        "gpu_bytes_per_triangle": rs[0]["gpu_bytes_per_triangle"],
        "gpu_scene_bytes": rs[0]["gpu_scene_bytes"],
    }
(out / "bvh_ab.json").write_text(json.dumps({
    "device": next(iter(runs.values()))["device"] if runs else None,
    "summary": summary,
    "runs": runs,
}, indent=1))
print(f"{'scene':16s} {'algo':5s} {'binary transport':>17s} {'wide':>8s} {'ratio':>6s}"
      f" {'binary image':>13s} {'wide':>8s} {'B/tri bin':>10s} {'wide':>6s}")
for (scene, algo) in sorted({(s, a) for (s, a, _) in groups}):
    b, w = summary.get(f"{scene}/{algo}/binary"), summary.get(f"{scene}/{algo}/wide")
    if not b or not w:
        continue
    print(f"{scene:16s} {algo:5s} {b['transport_ms']:17.3f} {w['transport_ms']:8.3f}"
          f" {w['transport_ms'] / b['transport_ms']:6.3f} {b['image_ms']:13.3f} {w['image_ms']:8.3f}"
          f" {b['gpu_bytes_per_triangle']:10.1f} {w['gpu_bytes_per_triangle']:6.1f}")
PY
