#!/usr/bin/env bash
# The training dataset, rendered with `lucid dataset` unless DATA_DIR/index.json exists already:
#   training/dataset_gpu.sh DATA_DIR
# (about 2 minutes and 3.2 GB on an H100). train_gpu.sh and compare_gpu.sh call it. LUCID names the
# lucid binary (default target/release/lucid, relative to the current directory); ROOMS, the
# procedural training rooms (32); FRAMES, the frames of a sequence (16); SEQUENCES, the sequences of
# a scene (2).
set -euo pipefail
data=${1:?usage: training/dataset_gpu.sh DATA_DIR}
if [ ! -f "$data/index.json" ]; then
  lucid=$(realpath "${LUCID:-target/release/lucid}")
  "$lucid" dataset --out "$data" --size 256x256 --frames "${FRAMES:-16}" --rooms "${ROOMS:-32}" \
    --validation-rooms 4 --sequences "${SEQUENCES:-2}" --reference-spp 256
fi
