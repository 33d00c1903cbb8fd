#!/usr/bin/env bash
# Forty-fifth session, run in the forty-sixth (one H200, 512 s; results in out/ and training/README.md). runs/v44 found
# the whole network fine-tuned for 4 minutes (`control`, its weights in runs/v44-motion-inputs/out/)
# 6.2% worse than the committed weights on the held-out `classroom` at 512x512 in PyTorch, but
# half and half with them (blend.py --t 0.5) 0.9% worse there and 3.0% better on `caustics`, whose
# FLIP the learned denoiser holds flat over the path while SVGF's falls. This measures the blends
# as the issue does: the held-out 1080p camera paths, 30 frames against 1024 samples, in the
# renderer (evaluate_gpu.sh), with the committed weights and SVGF beside them, at t = 0.25 and 0.5.
#   source .gpu/env.sh && WAIT_S=540 training/job_gpu.sh start training/runs/v45-control-blends/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait      (if the first command ran out first)
# About 321 s for the 30-frame evaluation and 66 s a weights file (two): some 460 s.
# .gpu/lucid.xz: a release lucid binary of main (64143fb's shaders or later).
set -u
rm -rf /tmp/out /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo /tmp/w-*.safetensors && cp -r . /tmp/repo && cd /tmp/repo
COMMITTED=passes/src/denoise/neural/lucid-rae-v3.safetensors
CONTROL=training/runs/v44-motion-inputs/out/w-control.safetensors
echo "START $(date +%s)"
for t in 25 5; do
  (cd training && python3 blend.py ../$COMMITTED ../$CONTROL --t 0.$t --out /tmp/w-control-blend-$t.safetensors)
done
FRAMES=30 FIRST=16 BENCH=0 MAPS=1 OIDN=0 SCENES="classroom caustics" LUCID=/tmp/bin/lucid \
  ALSO="/tmp/w-control-blend-25.safetensors /tmp/w-control-blend-5.safetensors" \
  training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
