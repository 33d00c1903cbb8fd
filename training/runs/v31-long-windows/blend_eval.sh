#!/usr/bin/env bash
# Thirty-seventh session, on a fresh one-GPU H200 after job.sh: the weights committed before it
# blended half and half with job.sh's `long` variant (burn-in 0-24; its weights in job.sh's
# weights.tgz), then held out over 30 frames beside the weights it came from (`neural`) and SVGF.
# The blend (`neural-b-long` in blend/metrics_*.csv) is what was shipped. Run from the project root,
# both weights files carried in .gpu/:
#   source .gpu/env.sh && training/runs/v31-long-windows/blend_eval.sh .gpu/before.safetensors \
#     .gpu/w-long.safetensors $OUT
# That session blended here (the same blend.py call) and carried the blend instead: 371 s.
set -eu
usage="usage: blend_eval.sh BEFORE.safetensors LONG.safetensors OUT_DIR"
before=$(realpath "${1:?$usage}")
long=$(realpath "${2:?$usage}")
out=${3:?$usage}
mkdir -p /tmp/bin && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
(cd training && python3 blend.py "$before" "$long" --t 0.5 --out /tmp/b-long.safetensors)
rm -rf /tmp/heldout-*
FRAMES=30 BENCH=0 MAPS=0 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  WEIGHTS="$before" ALSO=/tmp/b-long.safetensors training/evaluate_gpu.sh "$out"
