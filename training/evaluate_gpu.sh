#!/usr/bin/env bash
# The learned denoiser on the held-out scenes, on the NVIDIA machine, in one command:
#   training/evaluate_gpu.sh OUT_DIR
# Times it (`lucid bench`, classroom, 640x360 to 1920x1080), renders the held-out classroom and
# caustics camera paths at 1920x1080, 1 spp, against a 1024-sample reference (`lucid sequence`:
# no denoiser, SVGF's spatial filter per frame, SVGF, the learned denoiser), adds Intel Open Image
# Denoise per frame when pyoidn is importable, and evaluates (`lucid evaluate`). Writes
# OUT_DIR/bench_neural_<size>.json and OUT_DIR/metrics_<scene>.csv.
set -euo pipefail
out=${1:?usage: training/evaluate_gpu.sh OUT_DIR}
lucid=$(realpath "${LUCID:-target/release/lucid}")
frames=${FRAMES:-20}
mkdir -p "$out"
for size in 1920x1080 1280x720 854x480 640x360; do
  "$lucid" bench --scene classroom --algo pt --denoise neural --size "$size" --spp 1 --max-depth 8 \
    --frames 50 --warmup 5 --json "$out/bench_neural_$size.json" > /dev/null
  echo "bench $size done"
done
for scene in ${SCENES:-classroom caustics}; do
  dir=/tmp/heldout-$scene
  "$lucid" sequence --scene "$scene" --size 1920x1080 --frames "$frames" --reference-spp 1024 \
    --out "$dir" --no-evaluate
  if python3 -c "import pyoidn" 2>/dev/null; then
    python3 "$(dirname "$0")/oidn_baseline.py" "$dir"
  fi
  "$lucid" evaluate "$dir"
  cp "$dir/metrics.csv" "$out/metrics_$scene.csv"
done
