#!/usr/bin/env bash
# Forty-third session (one H200; run then: training/README.md): does the committed network, on the
# held-out scenes, lean too little on its history or on its gated filter? runs/v40 found
# `caustics`' FLIP flat from frame 2 on (0.0162-0.0176) while SVGF's falls (0.0240 to 0.0213), and
# `classroom`'s ordinary surfaces (0.1-0.5x the mean brightness, 73% of the pixels) flickering as
# much as SVGF's. Two probes, each the committed weights with one logit of `out` moved by +0.7
# everywhere (the history's weight, the gated filter's share), held out at 1080p over 30 frames
# beside the committed weights. Probes, not candidates: the held-out scenes choose nothing here.
#   cd training && for r in blend gate; do python3 shift_logit.py \
#     ../passes/src/denoise/neural/lucid-rae-v3.safetensors $r 0.7 \
#     --out ../.gpu/w-$r+0.7.safetensors; done
#   source .gpu/env.sh && WAIT_S=505 training/job_gpu.sh start training/runs/v41-logit-probe/job.sh
# It took 487 s (the 30-frame evaluation with the maps, and two more weights files).
# .gpu/lucid.xz: the release lucid binary of 4502076 (the committed weights' renderer).
set -u
rm -rf /tmp/out /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
echo "START $(date +%s)"
FRAMES=30 BENCH=0 MAPS=1 OIDN=0 SCENES="classroom caustics" LUCID=/tmp/bin/lucid \
  ALSO="$PWD/.gpu/w-blend+0.7.safetensors $PWD/.gpu/w-gate+0.7.safetensors" \
  training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
