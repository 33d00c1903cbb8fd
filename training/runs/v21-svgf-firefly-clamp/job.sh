#!/usr/bin/env bash
# SVGF's firefly clamp on one H200 (thirty-first session), from the repository root:
#   LUCID=/tmp/bin/lucid training/runs/v21-svgf-firefly-clamp/job.sh OUT
# The SVGF passes' time at 1920x1080 on `classroom` and `caustics` with the clamp on and off, two
# rounds alternating, then the held-out sequences with the shipped defaults (SVGF's clamp on, the
# edge pass for the learned denoiser only), then (unless EDGE_EMISSION=0) with the edge pass for
# SVGF too. Run with the clamp's headroom at 4 (`headroom4_1080p/`), then, EDGE_EMISSION=0, at 16.
set -euo pipefail
out=${1:?usage: job.sh OUT}
lucid=${LUCID:?the lucid binary}
mkdir -p "$out"
for round in 1 2; do
  for scene in classroom caustics; do
    for clamp in on off; do
      "$lucid" bench --scene "$scene" --algo pt --denoise svgf --size 1920x1080 --spp 1 --max-depth 8 \
        --frames 100 --warmup 10 --svgf-firefly-clamp "$clamp" \
        --json "$out/bench_${scene}_clamp_${clamp}_$round.json" > /dev/null
    done
  done
done
SCENES="classroom caustics" BENCH=0 LUCID="$lucid" training/evaluate_gpu.sh "$out/defaults"
if [ "${EDGE_EMISSION:-1}" = 1 ]; then
  SCENES="classroom caustics" BENCH=0 LUCID="$lucid" OPTIONS=--edge-emission \
    training/evaluate_gpu.sh "$out/edge_emission"
fi
echo JOBDONE
