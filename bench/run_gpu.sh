#!/usr/bin/env bash
# The GPU benchmark suite, as run on the NVIDIA machine (see bench/README.md):
#   bench/run_gpu.sh OUT_DIR [ALGOS]
# Runs `lucid bench` at 1920x1080, 1 spp, max depth 8 on every built-in scene for each algorithm
# (default: pt), SVGF on classroom at four resolutions, then Mitsuba 3 (cuda_ad_rgb) on its Cornell box when its package is unpacked at
# /tmp/mitsuba, and merges everything into OUT_DIR/results.json (single runs go to $RUNS).
set -euo pipefail
out=${1:?usage: bench/run_gpu.sh OUT_DIR [ALGOS]}
algos=${2:-pt}
lucid=${LUCID:-target/release/lucid}
frames=${FRAMES:-100}
runs=${RUNS:-/tmp/lucid-bench-runs}
mkdir -p "$out" "$runs"
"$lucid" info --json > "$runs/info.json"
for algo in $algos; do
  for scene in cornell-box cornell-teapot covered-light blinds-room classroom caustics; do
    "$lucid" bench --scene "$scene" --algo "$algo" --size 1920x1080 --spp 1 --max-depth 8 \
      --frames "$frames" --warmup 10 --json "$runs/${algo}_${scene}.json" > /dev/null
    echo "done $algo $scene"
  done
done
# The SVGF denoiser's cost at the resolutions the study timed its denoiser at.
if [ "${SVGF:-1}" = 1 ]; then
  for size in 1920x1080 1280x720 854x480 640x360; do
    "$lucid" bench --scene classroom --algo pt --denoise svgf --size "$size" --spp 1 --max-depth 8 \
      --frames "$frames" --warmup 10 --json "$runs/svgf_classroom_${size}.json" > /dev/null
    echo "done svgf $size"
  done
  # A frame after a scene change: the path tracer replays SVGF's gradient paths.
  "$lucid" bench --scene classroom --algo pt --denoise svgf --size 1920x1080 --spp 1 --max-depth 8 \
    --frames "$frames" --warmup 10 --dynamic --json "$runs/svgf_classroom_1920x1080_dynamic.json" > /dev/null
  echo "done svgf dynamic"
fi
if [ -d /tmp/mitsuba ]; then
  PYTHONPATH=/tmp/mitsuba python3 bench/mitsuba/bench_cornell.py --size 1920x1080 --spp 64 \
    --max-depth 8 --runs 5 --out "$runs/mitsuba_cornell.json"
fi
python3 - "$out" "$runs" <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])
runs = {p.stem: json.loads(p.read_text()) for p in sorted(pathlib.Path(sys.argv[2]).glob("*.json"))}
(out / "results.json").write_text(json.dumps(runs, indent=1))
for name, r in runs.items():
    if "frame_ms" in r:
        # Medians, as the targets are read; the maximum shows a start-up transient.
        print(f"{name:34s} {r['frame_ms']['median']:8.3f} ms (max {r['frame_ms']['max']:.3f})  "
              f"{r['paths_per_second']/1e9:6.3f} Gpaths/s  {r['rays_per_second']/1e9:6.3f} Grays/s  "
              f"(HDR image {r['image_ms']['median']:.3f} ms: {r['image_paths_per_second']/1e9:.3f} Gpaths/s)")
    elif "paths_per_s" in r or "paths_per_second" in r:
        print(name, {k: v for k, v in r.items() if "time" in k or "paths" in k})
PY
