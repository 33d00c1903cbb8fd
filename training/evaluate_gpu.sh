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
# CONVERGED_SPP, the reference rendered with that many samples and a third seed as one more method
# (what an exact image measures); REFERENCE_SPP, the reference's samples (1024, the issue's);
# OPTIONS, more options of `lucid sequence` (e.g. --edge-emission); OIDN=0 skips OIDN; MAPS=1 adds
# `lucid evaluate --maps` (OUT_DIR/summary_<scene>.txt and by_brightness_<scene>.csv, the light
# kept by brightness); SCENES, the held-out scenes (classroom caustics); FIRST, shorter lengths
# (space-separated) also evaluated from the same frames (`lucid evaluate --frames N`:
# OUT_DIR/metrics_<scene>_first<N>.csv, with MAPS the summary and by_brightness likewise). On a
# machine of several GPUs the scenes run at once, one a GPU (gpus.sh).
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
# shellcheck source=training/gpus.sh
. "$(dirname "$0")/gpus.sh"
# One held-out scene on GPU $2: its frames, OIDN's where it can, the metrics.
evaluate_scene() {
  local scene=$1 dir=/tmp/heldout-$1
  # shellcheck disable=SC2046 # gpu_env's and ALSO's words are separate arguments
  env $(gpu_env "$2") "$lucid" sequence --scene "$scene" --size 1920x1080 --frames "$frames" \
    --reference-spp "${REFERENCE_SPP:-1024}" --out "$dir" --no-evaluate ${SECOND_REFERENCE:+--second-reference} \
    ${CONVERGED_SPP:+--converged-reference-spp "$CONVERGED_SPP"} ${OPTIONS:-} ${WEIGHTS:+--neural-weights "$(realpath "$WEIGHTS")"} \
    $(for w in ${ALSO:-}; do echo "--also-neural-weights $(realpath "$w")"; done)
  if [ "${OIDN:-1}" != 0 ] && python3 -c "import pyoidn" 2>/dev/null; then
    # shellcheck disable=SC2046
    env $(gpu_env "$2") python3 "$(dirname "$0")/oidn_baseline.py" "$dir"
  fi
  evaluate_copy "$dir" "$scene" "$dir"
  for n in ${FIRST:-}; do
    evaluate_copy "$dir" "${scene}_first$n" "$dir/first-$n" --frames "$n"
  done
}
# `lucid evaluate DIR ARGS...`, then from RESULTS (where it wrote) its metrics, and with MAPS its
# summary and light by brightness, into OUT_DIR under SUFFIX: evaluate_copy DIR SUFFIX RESULTS ARGS...
evaluate_copy() {
  local dir=$1 suffix=$2 results=$3
  shift 3
  if [ "${MAPS:-0}" != 0 ]; then
    "$lucid" evaluate "$dir" --maps "$@" | tee "$out/summary_$suffix.txt"
    cp "$results/maps/by_brightness.csv" "$out/by_brightness_$suffix.csv"
  else
    "$lucid" evaluate "$dir" "$@"
  fi
  cp "$results/metrics.csv" "$out/metrics_$suffix.csv"
}
# The scenes one after another on one GPU, at once on several (scene K on GPU K % GPUS).
pids=()
k=0
for scene in ${SCENES:-classroom caustics}; do
  if [ "$GPUS" -gt 1 ]; then
    evaluate_scene "$scene" "$k" > "/tmp/evaluate-$scene.log" 2>&1 &
    pids+=($!)
  else
    evaluate_scene "$scene" "$k"
  fi
  k=$((k + 1))
done
failed=0
for pid in "${pids[@]}"; do
  wait "$pid" || failed=1
done
for scene in ${SCENES:-classroom caustics}; do
  if [ "$GPUS" -gt 1 ]; then tail -n 30 "/tmp/evaluate-$scene.log"; fi
done
exit $failed
