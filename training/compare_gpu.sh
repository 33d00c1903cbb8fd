#!/usr/bin/env bash
# Design choices measured against each other, in one command on the NVIDIA machine (within
# $BUDGET = 560 seconds, dataset included):
#   training/compare_gpu.sh OUT_DIR
# Renders the dataset into /tmp/lucid-dataset unless it is there (dataset_gpu.sh), then trains
# every variant of $VARIANTS at once (one background train.py each, variant K on GPU K % GPUS, see
# gpus.sh, so on one GPU all share it; the same --minutes: by default what $BUDGET leaves after the
# dataset and $RESERVE = 90 seconds for start-up, validation and export, at most 6), waits for
# them and writes into OUT_DIR:
#   compare.json          per variant: final validation relMSE, SSIM, FLIP, temporal instability, steps,
#                         seconds, parameters, FLOPs per pixel (and the ratios to the first variant)
#   variants.tar.gz       per variant: weights (<name>.safetensors), log (<name>.json) and output
#                         (<name>.log)
#   lucid-rae-v3.safetensors, train.json, neural_parity.safetensors
#                         the SHIP variant's weights under the shipping name (model.FORMAT),
#                         its log and the parity fixture from them
#   dataset.json          the dataset's index
# (6 files: what the GPU machine sends back is limited to 8.)
# A variant is MODEL:LOSS[:BURN_IN[:SEED[:WEIGHTS[:OPTIONS]]]] (train.py's --model, --loss,
# --burn-in, --seed, --weights: the loss terms' weights, comma-separated; a BURN_IN of J-K draws
# each step's from J to K, train.py's --burn-in-min J --burn-in K; OPTIONS: more train.py options
# as NAME=VALUE joined by +, e.g. fireflies=5e-5+widths=16,32,64,64,32,16) and is named
# MODEL-LOSS[-burnK][-seedN][-wA_B_C][-NAME_VALUE...]. VARIANTS defaults to
# "direct:l1grad:12 kernel:l1grad:12"; SEED (0) is the seed of variants that name none: the same
# seed draws the same training windows. Also: LUCID, SHARDS, ROOMS, FRAMES, SEQUENCES
# (dataset_gpu.sh), DATA, the dataset's folder; INIT, weights every variant starts from (e.g.
# lucid-rae-v2's: its first layer grows by the new inputs, at zero); MINUTES, each variant's
# training time; TRAIN_ARGS, more train.py arguments for every variant; SHIP, the variant exported
# under the shipping name (the first); GPUS_PER_VARIANT, the GPUs each variant trains on at once,
# data-parallel (parallel.py; default 1): variant K on GPUs K * G to K * G + G - 1 (G times the
# variants must not exceed the GPUs).
set -euo pipefail
out=${1:?usage: training/compare_gpu.sh OUT_DIR}
here=$(cd "$(dirname "$0")" && pwd)
data=${DATA:-/tmp/lucid-dataset}
budget=${BUDGET:-560}
reserve=${RESERVE:-90}
variants=${VARIANTS:-direct:l1grad:12 kernel:l1grad:12}
start=$(date +%s)
names=()
args=()
for v in $variants; do
  IFS=: read -r model loss burn seed weights options extra <<< "$v"
  if [ -z "$model" ] || [ -z "$loss" ] || [ -n "$extra" ]; then
    echo "variant '$v' is not MODEL:LOSS[:BURN_IN[:SEED[:WEIGHTS[:OPTIONS]]]]" >&2
    exit 2
  fi
  option_args=""
  if [ -n "$options" ]; then
    IFS=+ read -ra pairs <<< "$options"
    for pair in "${pairs[@]}"; do
      if [[ $pair != *=* ]]; then echo "variant '$v': option '$pair' is not NAME=VALUE" >&2; exit 2; fi
      option_args+=" --${pair%%=*} ${pair#*=}"
    done
  fi
  suffix=${options//[=,+]/_}
  name=$model-$loss${burn:+-burn$burn}${seed:+-seed$seed}${weights:+-w${weights//,/_}}${suffix:+-$suffix}
  for n in "${names[@]}"; do
    if [ "$n" = "$name" ]; then echo "variant $name twice" >&2; exit 2; fi
  done
  names+=("$name")
  burn_args="--burn-in ${burn:-0}"
  if [[ $burn == *-* ]]; then
    burn_args="--burn-in-min ${burn%-*} --burn-in ${burn#*-}"
  fi
  args+=("--model $model --loss $loss $burn_args --seed ${seed:-${SEED:-0}}${weights:+ --weights $weights}$option_args")
done
ship=${SHIP:-${names[0]}}
mkdir -p "$out"
out=$(realpath "$out")
data=$(realpath -m "$data")
init=${INIT:+$(realpath "$INIT")}
# shellcheck source=training/gpus.sh
. "$here/gpus.sh"
per_variant=${GPUS_PER_VARIANT:-1}
if [ "$per_variant" -gt 1 ] && [ $((per_variant * ${#names[@]})) -gt "$GPUS" ]; then
  echo "GPUS_PER_VARIANT=$per_variant for ${#names[@]} variant(s) needs $((per_variant * ${#names[@]})) GPUs; this machine has $GPUS" >&2
  exit 2
fi
"$here/dataset_gpu.sh" "$data"
echo "dataset: $(( $(date +%s) - start )) s, $(du -sh "$data" | cut -f1)"
(cd "$here" && python3 -c "import json, sys; from data import dataset_folders; json.dump([json.load(open(f / 'index.json')) for f in dataset_folders(sys.argv[1])], open(sys.argv[2], 'w'), indent=1)" "$data" "$out/dataset.json")
minutes=${MINUTES:-$(python3 -c "print(round(max(0.1, min(6.0, ($budget - $reserve - ($(date +%s) - $start)) / 60)), 2))")}
work=$(mktemp -d "${TMPDIR:-/tmp}/lucid-compare.XXXXXX")
cd "$here"
pids=()
for i in "${!names[@]}"; do
  name=${names[$i]}
  if [ "$per_variant" -gt 1 ]; then
    placement=$(gpu_set "$i" "$per_variant")
    launcher="parallel.py $per_variant"
  else
    placement=$(gpu_env "$i")
    launcher=""
  fi
  # shellcheck disable=SC2086 # the variant's, TRAIN_ARGS's, the placement's and launcher's words are separate
  env $placement PYTHONUNBUFFERED=1 python3 $launcher train.py --data "$data" --minutes "$minutes" ${args[$i]} \
    --out "$work/$name.safetensors" --log "$work/$name.json" ${init:+--init "$init"} ${TRAIN_ARGS:-} \
    > "$work/$name.log" 2>&1 &
  pids+=($!)
done
echo "training ${names[*]} for $minutes minutes each, in parallel on $GPUS GPU(s), $per_variant a variant"
failed=0
for i in "${!pids[@]}"; do
  if wait "${pids[$i]}"; then
    echo "${names[$i]}: $(tail -n 1 "$work/${names[$i]}.log")"
  else
    echo "${names[$i]}: failed (exit $?); the end of its output:"
    tail -n 20 "$work/${names[$i]}.log"
    failed=1
  fi
done
GPUS=$GPUS python3 - "$work" "$out/compare.json" "$minutes" "$(( $(date +%s) - start ))" "${names[@]}" <<'EOF'
import json, os, sys
from pathlib import Path

work, dest, minutes, elapsed, names = Path(sys.argv[1]), sys.argv[2], float(sys.argv[3]), int(sys.argv[4]), sys.argv[5:]
keys = ("relmse", "ssim", "flip", "temporal", "blotch", "light")
rows = []
for name in names:
    log = work / f"{name}.json"
    if not log.exists():
        rows.append({"name": name, "ok": False})
        continue
    r = json.loads(log.read_text())
    a = r["args"]
    rows.append({
        "name": name, "ok": True, "model": a["model"], "loss": a["loss"], "loss_weights": r["loss_weights"],
        "burn_in": a["burn_in"], "seed": a["seed"], "widths": a.get("widths"), "fireflies": a.get("fireflies"),
        "crop": a.get("crop"), "batch": a.get("batch"),
        "format": r["format"],
        **{k: r["final"].get(k) for k in keys},
        **({"watch": r["final"]["watch"]} if "watch" in r["final"] else {}),
        "steps": r["steps"], "train_seconds": r["train_seconds"], "total_seconds": r["total_seconds"],
        "parameters": r["parameters"], "macs_per_pixel": r["macs_per_pixel"], "flops_per_pixel": r["flops_per_pixel"],
        "device": r["device"], "weights": f"{name}.safetensors",
    })
base = rows[0] if rows and rows[0]["ok"] else None
if base:
    for row in rows[1:]:
        if row["ok"]:
            row["vs_" + base["name"]] = {
                k: round(row[k] / base[k], 4) if base[k] and row[k] is not None else None
                for k in keys + ("steps", "parameters", "flops_per_pixel")
            }
            if "watch" in row and "watch" in base:
                row["vs_" + base["name"]]["watch"] = {
                    k: round(row["watch"][k] / base["watch"][k], 4) if base["watch"][k] else None for k in keys
                }
summary = {
    "minutes": minutes,
    "seconds_before_export": elapsed,
    "gpus": int(os.environ["GPUS"]),
    "note": "variants trained at the same time, variant K on GPU K % gpus; validation from no history over whole "
    "validation sequences; relMSE, SSIM and FLIP as lucid evaluate computes them, temporal = mean |frame "
    "difference of output - reference's| in log space, blotch = the worst 8x8 block's excess brightness "
    "per frame over the reference mean's; watch = the same over the training sequences of TRAIN_ARGS' --watch",
    "variants": rows,
}
Path(dest).write_text(json.dumps(summary, indent=1))
print(json.dumps(summary, indent=1))
EOF
if [ -f "$work/$ship.json" ]; then
  format=$(python3 -c "import model; print(model.FORMAT)")
  if [ "$(python3 -c "import json; print(json.load(open('$work/$ship.json'))['format'])")" = "$format" ]; then
    cp "$work/$ship.safetensors" "$out/$format.safetensors"
    cp "$work/$ship.json" "$out/train.json"
    python3 make_parity.py --weights "$out/$format.safetensors" --data "$data" --out "$out/neural_parity.safetensors"
  else
    echo "$ship is no $format model: nothing exported under the shipping name"
  fi
else
  echo "no $ship run: nothing exported under the shipping name"
fi
tar -czf "$out/variants.tar.gz" -C "$work" .
rm -r "$work"
echo "total: $(( $(date +%s) - start )) s"
exit $failed
