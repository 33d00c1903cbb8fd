#!/usr/bin/env bash
# Thirty-sixth session (one H200): the held-out paths at 30 frames, as issue #12's own table was
# measured, and the committed weights with their running means capped at fewer frames
# (`history_frames` metadata) on the same frames. On the NVIDIA machine, from the repository root:
#   job.sh OUT thirty      the committed weights and SVGF (thirty-frames/)
#   job.sh OUT history     the same with `history_frames` 20 and 12 beside them (history-frames/;
#                          `caustics` ran, `classroom` did not finish in the device time left)
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -eu
out=${1:?usage: job.sh OUT thirty|history}
mkdir -p /tmp/bin && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/heldout-*
also=""
if [ "${2:?}" = history ]; then
  committed=passes/src/denoise/neural/lucid-rae-v3.safetensors
  for n in 20 12; do
    (cd training && python3 set_metadata.py "../$committed" history_frames=$n --out "/tmp/w-h$n.safetensors")
    also="$also /tmp/w-h$n.safetensors"
  done
fi
FRAMES=30 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" ALSO="$also" LUCID=/tmp/bin/lucid \
  training/evaluate_gpu.sh "$out"
