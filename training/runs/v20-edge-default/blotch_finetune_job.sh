#!/usr/bin/env bash
# Thirtieth session (two H200s): fine-tunings of the committed weights against blotches, for the
# edge pass as the learned denoiser's default (training/README.md, "The edge pass as the learned
# denoiser's default"). A fresh 512x512 dataset as the twenty-ninth session's (8 shards, 6
# procedural rooms a shard, SEED_OFFSET 48), then two 5-minute fine-tunings at the lower rate 5e-4,
# one a GPU, with the blotch term beyond a 0.3 margin at weights 0.2 and 0.1 and a quarter of the
# windows started cold (as the lavapipe blotch test starts); each result and its half-and-half blend
# with the committed weights held out at 1080p with the edge pass on for every method. On one GPU
# (the two-GPU machine was not lent): SHARDS=4 MINUTES=5 BLOTCH_WEIGHTS=0.2.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
GPUS=$(nvidia-smi -L | wc -l)
export GPUS
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-4+cold=0.25+blotch-margin=0.3
cp passes/src/denoise/neural/lucid-rae-v3.safetensors /tmp/committed.safetensors
variants=""
for b in ${BLOTCH_WEIGHTS:-0.2 0.1}; do variants+=" kernel:l1gradflip:0-12:::$W+blotch=$b"; done
LUCID=/tmp/bin/lucid SHARDS=${SHARDS:-8} SEED_OFFSET=48 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="${variants# }" \
  INIT=/tmp/committed.safetensors MINUTES=${MINUTES:-5} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  b=$(basename "$f" .safetensors | sed -e 's/.*_blotch_/blotch/')
  cp "$f" "/tmp/w-$b.safetensors"; cp "${f%.safetensors}.json" "/tmp/out/$b.json"
  python3 training/blend.py /tmp/committed.safetensors "$f" --t 0.5 --out "/tmp/b-$b.safetensors"
done
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors b-*.safetensors)
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid OPTIONS=--edge-emission \
  ALSO="$(ls /tmp/w-*.safetensors /tmp/b-*.safetensors | tr '\n' ' ')" \
  training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
echo JOB-END
