#!/usr/bin/env bash
# The held-out evaluation of runs/v33-spatial-variance/job.sh's weights (weights.tgz beside this
# file: w-control, w-spatial4 and their blends with the committed weights, b-control, b-spatial4)
# beside the committed weights and SVGF: `caustics`, then `classroom`, 1080p, over 30 frames and
# over their first 20 as a 20-frame sequence, with `--maps`. .gpu/lucid.xz: the release lucid
# binary of a commit whose features pass reads `spatial_variance_frames` (the thirty-eighth
# session's or later). Start and wait with training/job_gpu.sh (about 320 s, plus about 66 s a
# weights file: some 590 s):
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v33-spatial-variance/eval.sh
#   source .gpu/env.sh && training/job_gpu.sh wait
# Writes the metrics, summary and by_brightness per scene into /tmp/out (job_gpu.sh brings them
# back as one out.tgz).
set -u
rm -rf /tmp/out /tmp/v33 /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out /tmp/v33
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
tar xzf training/runs/v33-spatial-variance/weights.tgz -C /tmp/v33
echo "EVAL-START $(date +%s)"
FRAMES=30 FIRST=20 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO="$(echo /tmp/v33/*.safetensors)" training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
