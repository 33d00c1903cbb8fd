#!/usr/bin/env bash
# The firefly clamp's headroom on the held-out `caustics` path at 1920x1080 (one H200), from the
# repository root:  LUCID=/tmp/bin/lucid training/runs/v21-svgf-firefly-clamp/headroom_job.sh OUT
set -euo pipefail
out=${1:?usage: headroom_job.sh OUT}
mkdir -p "$out"
for headroom in ${HEADROOMS:-32 64 256}; do
  SCENES=caustics BENCH=0 LUCID="${LUCID:?the lucid binary}" OPTIONS="--svgf-firefly-headroom $headroom" \
    training/evaluate_gpu.sh "/tmp/headroom-$headroom" > /dev/null 2>&1
  cp "/tmp/headroom-$headroom/metrics_caustics.csv" "$out/metrics_caustics_headroom_$headroom.csv"
  echo "headroom $headroom done"
done
echo JOBDONE
