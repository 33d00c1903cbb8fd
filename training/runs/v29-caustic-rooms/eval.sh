#!/usr/bin/env bash
# Thirty-fifth session, on the NVIDIA machine: weights files held out at 1080p beside the committed
# weights and SVGF (`training/evaluate_gpu.sh`, `caustics` then `classroom`, 20 frames against the
# 1024-sample reference, `lucid evaluate --maps`, no OIDN):
#   eval.sh OUT WEIGHTS...
# Run three times: the two trained variants (eval-trained/, followed by `ROUNDS=1
# SIZES=1920x1080 bench/neural_ab_gpu.sh OUT/ab lucid lucid:w-mix-half-fireflies.safetensors`,
# the mix's time and the parity test on both inference paths), the plain blends (eval-blend/) and
# the blends with their own mix (eval-blend-own-mix/).
set -eu
out=${1:?usage: eval.sh OUT WEIGHTS...}
shift
mkdir -p /tmp/bin && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" ALSO="$*" LUCID=/tmp/bin/lucid training/evaluate_gpu.sh "$out"
