#!/usr/bin/env bash
# Thirtieth session (one H200), after the lavapipe findings in training/README.md ("The edge pass
# as the learned denoiser's default"): the parity test under the validation layer with the committed
# weights and the denoiser's time at 1080p and 854x480 (bench/neural_ab_gpu.sh), then the held-out
# paths at 1080p with the edge pass on for every method, the committed weights beside their blend
# with runs/v17-crop/blotch_cold.safetensors at t = 0.2 (.gpu/blotch_blend_t0.2.safetensors:
# `blend.py lucid-rae-v3.safetensors runs/v17-crop/blotch_cold.safetensors --t 0.2`).
# .gpu/lucid.xz and .gpu/neural_parity.xz: the release binaries of the commit this file came with.
set -u
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
echo "AB-START $(date +%s)"
bench/neural_ab_gpu.sh /tmp/out/ab lucid
echo "AB-END $? $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid OPTIONS=--edge-emission \
  ALSO="$PWD/.gpu/blotch_blend_t0.2.safetensors" training/evaluate_gpu.sh /tmp/eval
echo "HELDOUT-END $? $(date +%s)"
for s in classroom caustics; do cp "/tmp/eval/metrics_$s.csv" "/tmp/out/metrics_${s}_edge_emission_blotch_blend.csv"; done
echo JOB-END
