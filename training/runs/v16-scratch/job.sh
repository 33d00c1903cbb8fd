#!/usr/bin/env bash
# Prepared in session 24 for the next (4 GPUs, the session's whole device time, about 1450 s): the
# committed network (four scales) trained FROM SCRATCH, data-parallel on all four GPUs for 14
# minutes, on 16 shards of rooms (SEED_OFFSET=16, as session 24's), with every option the committed
# weights gathered over ten sessions of fine-tuning (FLIP term, fireflies, burn-in drawn 0-12);
# then the held-out evaluation on GPUs 0-1 with the new weights beside the committed ones, while
# GPU 3 A/Bs the loose spheres (.gpu/ab_loose.sh, .gpu/bins6.tar.xz). .gpu/lucid.xz was built from
# c922fb6; rebuild it if HEAD's shaders have changed.
set -u
export GPUS=4
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W4=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4
LUCID=/tmp/bin/lucid SHARDS=16 SEED_OFFSET=16 ROOMS=24 FRAMES=32 SEQUENCES=1 \
  GPUS_PER_VARIANT=4 VARIANTS="kernel:l1gradflip:0-12:::$W4" \
  MINUTES=14 TRAIN_ARGS="--batch 24 --watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  cp "$f" /tmp/w-scratch.safetensors; cp "${f%.safetensors}.json" /tmp/out/scratch.json
done
cp /tmp/train-out/compare.json /tmp/train-out/dataset.json /tmp/out/
tar czf /tmp/out.tgz -C /tmp out w-scratch.safetensors
(LUCID_DEVICE='#3' OUT=/tmp/out bash .gpu/ab_loose.sh > /tmp/out/ab_loose.log 2>&1) &
ab=$!
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid ALSO="/tmp/w-scratch.safetensors" \
  training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
wait $ab
cp /tmp/eval/metrics_*.csv /tmp/out/
tar czf /tmp/out.tgz -C /tmp out w-scratch.safetensors
echo JOB-END
