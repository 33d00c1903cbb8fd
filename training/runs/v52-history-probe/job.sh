#!/usr/bin/env bash
# Forty-eighth session (one H200). runs/v41 moved the history's logit by hand (shift_logit.py) and
# found more history worse on both held-out paths (FLIP +6.7% and +6.9% at +0.7, the excess growing
# from 1.03x at frame 1 to 1.08-1.10x at frame 29), but on the H200 the output's history was then
# truncated every frame (fixed in the forty-seventh session), which compounds more the more history
# a pixel keeps. Now that it is stored exactly, and against SVGF with its steps rounded (runs/v51:
# `caustics`' ratio rises from 0.80x over frames 0-4 to 0.90x at frame 28 as SVGF's error falls with
# the slowing camera and the learned denoiser's stays flat), does the network lean on its history
# too little on the held-out paths? A probe, not a candidate (the held-out scenes choose nothing):
# the history's logit moved by -0.35, +0.35 and +0.7, held out at 1080p over 30 frames against 1024
# samples beside the committed weights. Then `covered-light`'s path tracing three times (#15: the
# forty-eighth session's standings run had its first 30 frames at 4.2 ms).
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v52-history-probe/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait      (if the first command ran out first)
# About 560 s. .gpu/lucid_int.xz: the release binary of c51f565.
set -u
rm -rf /tmp/out /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid_int.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
COMMITTED=passes/src/denoise/neural/lucid-rae-v3.safetensors
(cd training && for s in -0.35 +0.35 +0.7; do
  python3 shift_logit.py ../$COMMITTED blend "$s" --out "/tmp/w-blend$s.safetensors"
done)
echo "START $(date +%s)"
FRAMES=30 FIRST=16 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO="/tmp/w-blend-0.35.safetensors /tmp/w-blend+0.35.safetensors /tmp/w-blend+0.7.safetensors" \
  training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
for run in 1 2 3; do
  /tmp/bin/lucid bench --scene covered-light --algo pt --size 1920x1080 --spp 1 --max-depth 8 \
    --frames 100 --warmup 10 --json "/tmp/out/bench_covered_light_$run.json" > /dev/null
done
echo "JOB-END $(date +%s)"
