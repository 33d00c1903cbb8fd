#!/usr/bin/env bash
# The firefly clamp's headroom and the history it needs, swept at 960x540 on the held-out paths
# (20 frames, 1024-sample references), one H200, from the repository root:
#   LUCID=/tmp/bin/lucid training/runs/v21-svgf-firefly-clamp/sweep_job.sh OUT
# A variant is CLAMP:HEADROOM:MIN_HISTORY (MIN_HISTORY 0: from a pixel's second frame, and its
# first frame against its neighbours; 4: only where the history holds 4 frames). The experiment's
# binary read HEADROOM and MIN_HISTORY from LUCID_FH and LUCID_FMIN; the shipped one takes the
# headroom from --svgf-firefly-headroom and has MIN_HISTORY 0 built in (`FIREFLY_MIN_HISTORY` 1 and
# the first-frame bound in shaders/svgf/temporal.comp), so only the MIN_HISTORY 0 variants rerun.
set -euo pipefail
out=${1:?usage: sweep_job.sh OUT}
lucid=${LUCID:?the lucid binary}
mkdir -p "$out"
for scene in caustics classroom; do
  for variant in ${VARIANTS:-off:4:0 on:4:0 on:16:0 on:4:4 on:16:4}; do
    IFS=: read -r clamp headroom min_history <<< "$variant"
    dir=/tmp/sweep-$scene-$clamp-$headroom-$min_history
    LUCID_FH=$headroom LUCID_FMIN=$min_history "$lucid" sequence --scene "$scene" --size 960x540 \
      --frames 20 --reference-spp 1024 --svgf-firefly-clamp "$clamp" --svgf-firefly-headroom "$headroom" --out "$dir" --no-evaluate > /dev/null 2>&1
    "$lucid" evaluate "$dir" > /dev/null 2>&1
    cp "$dir/metrics.csv" "$out/metrics_${scene}_${clamp}_${headroom}_${min_history}.csv"
    echo "$scene $variant done"
  done
done
echo JOBDONE
