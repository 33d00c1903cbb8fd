#!/usr/bin/env bash
# Thirty-fourth session (one H200): the kernel decoder's per-pixel mix of log-space and
# linear-space filtering (kernel_model.py, `linear_mix`), trained. From the committed weights (the
# mix's logit started at sigmoid(-3)), the thirtieth session's fine-tuning recipe (as
# runs/v22-neural-firefly-clamp/finetune_job.sh) on a fresh dataset (4 shards, SEED_OFFSET 64),
# twice at once on the one GPU: the mix alone, and the mix with the light of 8x8 blocks in the loss
# (`--energy 1`, losses.energy_l1). Then both held out at 1080p beside the committed weights,
# `caustics` first, with `lucid evaluate --maps` for the light each keeps. Writes into /tmp/out as
# each step ends (job_gpu.sh brings it back): compare.json, <variant>.json, weights.tgz,
# metrics_<scene>.csv, by_brightness_<scene>.csv, summary_<scene>.txt.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-4+cold=0.25+blotch-margin=0.3+blotch=0.2+linear-mix=
cp passes/src/denoise/neural/lucid-rae-v3.safetensors /tmp/committed.safetensors
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=64 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-12:::$W kernel:l1gradflip:0-12:::$W+energy=1" \
  INIT=/tmp/committed.safetensors MINUTES=${MINUTES:-5} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  case "$f" in *energy*) n=mix-energy ;; *) n=mix ;; esac
  cp "$f" "/tmp/w-$n.safetensors"; cp "${f%.safetensors}.json" "/tmp/out/$n.json"
done
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors)
for scene in caustics classroom; do
  dir=/tmp/heldout-$scene
  /tmp/bin/lucid sequence --scene "$scene" --size 1920x1080 --frames 20 --reference-spp 1024 \
    --out "$dir" --no-evaluate $(for w in /tmp/w-*.safetensors; do echo "--also-neural-weights $w"; done) > /dev/null
  /tmp/bin/lucid evaluate "$dir" --maps > "/tmp/out/summary_$scene.txt"
  cp "$dir/metrics.csv" "/tmp/out/metrics_$scene.csv"
  cp "$dir/maps/by_brightness.csv" "/tmp/out/by_brightness_$scene.csv"
  echo "DONE $scene $(date +%s)"
done
echo JOB-END
