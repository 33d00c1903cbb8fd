#!/usr/bin/env bash
# The training dataset, rendered with `lucid dataset` unless DATA_DIR holds one already:
#   training/dataset_gpu.sh DATA_DIR
# SHARDS (default 1) `lucid dataset` processes run at once, each into DATA_DIR/shard-K with seed K
# (rooms random-room-<1000 K + i>): shard 0 with the built-in scenes and the validation rooms, the
# others with procedural training rooms only (`data.py` reads the shards as one dataset). LUCID
# names the lucid binary (default target/release/lucid, relative to the current directory); ROOMS,
# the procedural training rooms of a shard (32); FRAMES, the frames of a sequence (16); SEQUENCES,
# the sequences of a scene (2); SEED_OFFSET (default 0), added to the seeds of shards 1 and on, so
# that a dataset of other training rooms can be rendered with the same validation rooms and built-in
# scenes (shard 0 keeps seed 0); ROOMS_FIRST, shard 0's procedural training rooms (default ROOMS: with
# the built-in scenes and the validation rooms it is the slowest shard); SIZE, the frames' size
# (256x256); SIZE_FIRST, shard 0's (default SIZE: its built-in scenes and validation rooms may stay
# smaller than larger training rooms, which then cost less to render); STOPS, the share of
# sequences whose camera comes to rest (`lucid dataset --stops`, default 0). On a machine of several
# GPUs shard K renders on GPU K % GPUS (gpus.sh). compare_gpu.sh calls it.
set -euo pipefail
data=${1:?usage: training/dataset_gpu.sh DATA_DIR}
if [ -f "$data/index.json" ] || [ -f "$data/shard-0/index.json" ]; then
  exit 0
fi
lucid=$(realpath "${LUCID:-target/release/lucid}")
# shellcheck source=training/gpus.sh
. "$(dirname "$0")/gpus.sh"
shards=${SHARDS:-1}
pids=()
for ((k = 0; k < shards; k++)); do
  seed=$k
  rooms=${ROOMS:-32}
  size=${SIZE:-256x256}
  if [ "$k" -eq 0 ]; then
    rooms=${ROOMS_FIRST:-$rooms}
    size=${SIZE_FIRST:-$size}
    extra=(--validation-rooms 4)
  else
    extra=(--validation-rooms 0 --no-builtin)
    seed=$((k + ${SEED_OFFSET:-0}))
  fi
  dest=$data
  if [ "$shards" -gt 1 ]; then dest=$data/shard-$k; fi
  # shellcheck disable=SC2046 # gpu_env's assignments are separate words
  env $(gpu_env "$k") "$lucid" dataset --out "$dest" --size "$size" --frames "${FRAMES:-16}" --rooms "$rooms" \
    --sequences "${SEQUENCES:-2}" --reference-spp 256 --seed "$seed" --stops "${STOPS:-0}" "${extra[@]}" &
  pids+=($!)
done
for pid in "${pids[@]}"; do
  wait "$pid"
done
