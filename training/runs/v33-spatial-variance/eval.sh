#!/usr/bin/env bash
# The held-out evaluation of spatial4's blend with the committed weights (b-spatial4 in
# runs/v33-spatial-variance/weights.tgz; the four files alone were held out by
# runs/v34-large-frames/job.sh, and b-spatial4 on `classroom` over 20 frames in the thirty-ninth
# session) beside the committed weights and SVGF: `caustics`, then `classroom`, 1080p, over 30
# frames and over their first 20 as a 20-frame sequence, with `--maps`. First the parity test
# under the validation layer on both inference paths (nine fixtures, the spatial variances' among
# them) and the denoiser's time at 1080p with the committed weights and with b-spatial4
# (bench/neural_ab_gpu.sh, one round: run bench/pack_parity.sh before carrying .gpu).
# .gpu/lucid.xz: the release lucid binary of a commit whose features pass reads
# `spatial_variance_frames` (the thirty-eighth session's or later). Start and wait with
# training/job_gpu.sh (about 30 s for the parity test and the time, 320 s for the evaluation and
# 66 s for the extra weights file: some 420 s):
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v33-spatial-variance/eval.sh
#   source .gpu/env.sh && training/job_gpu.sh wait
# Writes ab/ (the parity log and the times), then the metrics, summary and by_brightness per scene
# into /tmp/out (job_gpu.sh brings them back as one out.tgz).
set -u
rm -rf /tmp/out /tmp/v33 /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out /tmp/v33
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
tar xzf training/runs/v33-spatial-variance/weights.tgz -C /tmp/v33
ROUNDS=1 SIZES=1920x1080 bench/neural_ab_gpu.sh /tmp/out/ab lucid lucid:/tmp/v33/b-spatial4.safetensors
echo "PARITY-END $? $(date +%s)"
echo "EVAL-START $(date +%s)"
FRAMES=30 FIRST=20 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO=/tmp/v33/b-spatial4.safetensors training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
