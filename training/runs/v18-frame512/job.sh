#!/usr/bin/env bash
# Prepared in the twenty-seventh session (lost there with its machine), run in the twenty-eighth
# (4 GPUs): does more context per training window help further? Whole
# 256x256 frames beat 128x128 crops (twenty-sixth session, runs/v17-crop); here the dataset's
# frames are 512x512 (the same bytes: 6 procedural rooms a shard instead of 24, shard 0 only the
# built-in scenes and the validation rooms), and the crop is swept at the same pixels a step
# (524,288, within 4%), one variant a GPU, 8 minutes each, from the committed weights:
#   0 four scales, crop 256, batch 8 (the control: what the twenty-sixth session's frames held)
#   1 four scales, crop 368, batch 4
#   2 four scales, crop 512 (whole frames), batch 2
#   3 five scales, crop 512, batch 2 (the sixteenth's head from zero: at 512 its grid is 32x32)
# then the held-out evaluation at 1080p of all of them beside the committed weights.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
export GPUS=4
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16
cp passes/src/denoise/neural/lucid-rae-v3.safetensors /tmp/committed.safetensors
LUCID=/tmp/bin/lucid SHARDS=16 SEED_OFFSET=32 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-12:::$W+scales=4+crop=256+batch=8 kernel:l1gradflip:0-12:::$W+scales=4+crop=368+batch=4 kernel:l1gradflip:0-12:::$W+scales=4+crop=512+batch=2 kernel:l1gradflip:0-12:::$W+scales=5+crop=512+batch=2" \
  INIT=/tmp/committed.safetensors MINUTES=${MINUTES:-8} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  short=$(basename "$f" | sed -e 's/.*widths_16_32_64_64_32_16_//')
  cp "$f" "/tmp/w-$short"; cp "${f%.safetensors}.json" "/tmp/out/${short%.safetensors}.json"
done
cp /tmp/train-out/compare.json /tmp/train-out/dataset.json /tmp/out/
tar czf /tmp/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors)
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="$(ls /tmp/w-*.safetensors | tr '\n' ' ')" \
  training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo JOB-END
