#!/usr/bin/env bash
# The learned denoiser on the held-out scenes, on the NVIDIA machine, in one command:
#   training/evaluate_gpu.sh OUT_DIR
# Times it on every inference path (`bench_gpu.sh`), renders the held-out classroom and
# caustics camera paths at 1920x1080, 1 spp, against a 1024-sample reference (`lucid sequence`:
# no denoiser, SVGF's spatial filter per frame, SVGF, the learned denoiser), adds Intel Open Image
# Denoise per frame when pyoidn is importable, and evaluates (`lucid evaluate`). Writes
# OUT_DIR/neural_times.json (BENCH=0 skips the timing) and OUT_DIR/metrics_<scene>.csv. WEIGHTS,
# a weights file to use instead of the committed ones; ALSO, more weights files (space-separated),
# each evaluated as one more method `neural-<file stem>` on the same frames; SECOND_REFERENCE set, the
# reference rendered again with another seed as one more method (the reference's own noise);
# OPTIONS, more options of `lucid sequence` (e.g. --edge-emission).
set -euo pipefail
out=${1:?usage: training/evaluate_gpu.sh OUT_DIR}
lucid=$(realpath "${LUCID:-target/release/lucid}")
frames=${FRAMES:-20}
mkdir -p "$out"
if [ "${BENCH:-1}" != 0 ]; then
  bench=$(mktemp -d)
  LUCID="$lucid" "$(dirname "$0")/bench_gpu.sh" "$bench"
  cp "$bench/neural_times.json" "$out/"
fi
for scene in ${SCENES:-classroom caustics}; do
  dir=/tmp/heldout-$scene
  "$lucid" sequence --scene "$scene" --size 1920x1080 --frames "$frames" --reference-spp 1024 \
    --out "$dir" --no-evaluate ${SECOND_REFERENCE:+--second-reference} ${OPTIONS:-} ${WEIGHTS:+--neural-weights "$(realpath "$WEIGHTS")"} \
    $(for w in ${ALSO:-}; do echo "--also-neural-weights $(realpath "$w")"; done)
  if python3 -c "import pyoidn" 2>/dev/null; then
    python3 "$(dirname "$0")/oidn_baseline.py" "$dir"
  fi
  "$lucid" evaluate "$dir"
  cp "$dir/metrics.csv" "$out/metrics_$scene.csv"
done
