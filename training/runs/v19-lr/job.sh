#!/usr/bin/env bash
# Twenty-ninth session (4 GPUs): the fine-tuning's learning rate. Every fine-tuning so far ran at
# train.py's default 2e-3 (cosine to zero), the rate for training from scratch, and half-and-half
# blends with the weights it started from won again and again (twentieth, twenty-third and
# twenty-eighth sessions): a sign that the fine-tunings overshoot. Here, on a fresh 512x512 dataset
# of the twenty-eighth session's size (6 procedural rooms a shard, other rooms: SEED_OFFSET 48), its
# best variant (four scales, crop 368, batch 4) is fine-tuned from the committed weights for 8
# minutes at four rates, one a GPU: 2e-3 (the control), 1e-3, 5e-4, 2e-4. Then each result, and its
# half-and-half blend with the committed weights, is held out at 1080p beside the committed ones.
# On fewer GPUs (the four-GPU machine was lost before its evaluation and was then not lent): SHARDS
# and LRS, e.g. SHARDS=8 LRS="2e-3 5e-4" MINUTES=6 on two.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
GPUS=$(nvidia-smi -L | wc -l)
export GPUS
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4
cp passes/src/denoise/neural/lucid-rae-v3.safetensors /tmp/committed.safetensors
variants=""
for lr in ${LRS:-2e-3 1e-3 5e-4 2e-4}; do variants+=" kernel:l1gradflip:0-12:::$W+lr=$lr"; done
LUCID=/tmp/bin/lucid SHARDS=${SHARDS:-16} SEED_OFFSET=48 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="${variants# }" \
  INIT=/tmp/committed.safetensors MINUTES=${MINUTES:-8} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  lr=$(basename "$f" .safetensors | sed -e 's/.*_lr_//')
  cp "$f" "/tmp/w-lr$lr.safetensors"; cp "${f%.safetensors}.json" "/tmp/out/lr$lr.json"
  python3 training/blend.py /tmp/committed.safetensors "$f" --t 0.5 --out "/tmp/b-lr$lr.safetensors"
done
cp /tmp/train-out/compare.json /tmp/train-out/dataset.json /tmp/out/
tar czf /tmp/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors b-*.safetensors)
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="$(ls /tmp/w-*.safetensors /tmp/b-*.safetensors | tr '\n' ' ')" \
  training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo JOB-END
