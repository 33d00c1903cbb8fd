#!/usr/bin/env bash
# Data and training on the NVIDIA machine, in one command (about 9 minutes on an H100):
#   training/train_gpu.sh OUT_DIR
# Renders the dataset with `lucid dataset` into /tmp/lucid-dataset (dataset_gpu.sh) unless it is
# there, trains for $MINUTES minutes (default: what is left of $BUDGET = 540 seconds, at most 6),
# and writes OUT_DIR/lucid-rae-v2.safetensors (weights), OUT_DIR/train.json (log and validation
# metrics), OUT_DIR/dataset.json (the dataset's index) and OUT_DIR/neural_parity.safetensors (the
# parity fixture from a validation crop). LUCID names the lucid binary (default target/release/lucid);
# INIT, weights to start from (e.g. the committed ones); ROOMS, the procedural training rooms (32);
# DATA, the dataset's folder; TRAIN_ARGS, more arguments for train.py.
set -euo pipefail
out=${1:?usage: training/train_gpu.sh OUT_DIR}
data=${DATA:-/tmp/lucid-dataset}
budget=${BUDGET:-540}
mkdir -p "$out"
out=$(realpath "$out")
data=$(realpath -m "$data")
init=${INIT:+$(realpath "$INIT")}
start=$(date +%s)
"$(dirname "$0")/dataset_gpu.sh" "$data"
echo "dataset: $(( $(date +%s) - start )) s, $(du -sh "$data" | cut -f1)"
cp "$data/index.json" "$out/dataset.json"
# Train for what the command's time budget leaves (validation and export take about a minute).
minutes=${MINUTES:-$(python3 -c "print(max(0.5, min(6.0, ($budget - ($(date +%s) - $start)) / 60 - 1.2)))")}
echo "training for $minutes minutes"
cd "$(dirname "$0")"
python3 train.py --data "$data" --minutes "$minutes" --out "$out/lucid-rae-v2.safetensors" --log "$out/train.json" \
  ${init:+--init "$init"} ${TRAIN_ARGS:-}
python3 make_parity.py --weights "$out/lucid-rae-v2.safetensors" --data "$data" --out "$out/neural_parity.safetensors"
echo "total: $(( $(date +%s) - start )) s"
