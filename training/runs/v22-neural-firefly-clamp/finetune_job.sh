#!/usr/bin/env bash
# Thirty-second session (one H200): does the fine-tuning learn a better settled state when the loss
# sees longer windows? The thirtieth session's fine-tuning against blotches (blotch term 0.2 beyond
# 0.3, a quarter of the windows cold, lr 5e-4, 368x368 crops of 512x512 frames) from the committed
# weights on a fresh dataset (4 shards, SEED_OFFSET 56), twice at once on the one GPU: 8 frames
# with a loss in batches of 4 windows (as then) and 16 frames in batches of 2 (the same frames with
# a loss a step); each and its half-and-half blend with the committed weights held out at 1080p.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-4+cold=0.25+blotch-margin=0.3+blotch=0.2
cp passes/src/denoise/neural/lucid-rae-v3.safetensors /tmp/committed.safetensors
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=56 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-12:::$W kernel:l1gradflip:0-12:::$W+frames=16+batch=2" \
  INIT=/tmp/committed.safetensors MINUTES=${MINUTES:-5} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  case "$f" in *frames_16*) n=frames16 ;; *) n=frames8 ;; esac
  cp "$f" "/tmp/w-$n.safetensors"; cp "${f%.safetensors}.json" "/tmp/out/$n.json"
  python3 training/blend.py /tmp/committed.safetensors "$f" --t 0.5 --out "/tmp/b-$n.safetensors"
done
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors b-*.safetensors)
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="$(ls /tmp/w-*.safetensors /tmp/b-*.safetensors | tr '\n' ' ')" \
  training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
echo JOB-END
