#!/usr/bin/env bash
# Twenty-eighth session, right after job.sh on the same machine (its /tmp still there): each of the
# two whole-frame-context fine-tunings blended half and half with the committed weights
# (training/blend.py, t = 0.5), then both blends held out at 1080p beside everything job.sh
# evaluated. The first blend (b-368) is what was shipped.
set -u
cd /tmp/repo
for v in 368_batch_4 512_batch_2; do
  python3 training/blend.py /tmp/committed.safetensors /tmp/w-scales_4_crop_${v}.safetensors \
    --t 0.5 --out /tmp/b-${v%%_*}.safetensors || exit 1
done
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="/tmp/b-368.safetensors /tmp/b-512.safetensors" training/evaluate_gpu.sh /tmp/eval2
mkdir -p "$OUT/e" && cp /tmp/eval2/metrics_*.csv "$OUT/e/" && cp /tmp/b-368.safetensors "$OUT/"
