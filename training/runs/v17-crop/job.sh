#!/usr/bin/env bash
# Twenty-sixth session (4 GPUs): does the training crop limit what the coarse kernel scales learn?
# Every training so far drew 128x128 crops, so a window's eighth-resolution scale is 16x16 pixels
# and its sixteenth 8x8, with borders replicated across most of their 5x5 kernels' reach; the
# renderer runs them over 1920x1080 frames. Here the dataset's whole 256x256 frames (batch 6: the
# same pixels a step as 24 crops of 128) against the control, one variant a GPU, 9 minutes each,
# from the committed weights on the twenty-fourth session's rooms (SEED_OFFSET=16):
#   0 control: four scales, crop 128, batch 24 (the twenty-fourth session's "four scales, plain")
#   1 four scales, crop 256, batch 6
#   2 five scales, crop 256, batch 6 (the sixteenth's head from zero, as widen_scales.py starts it)
#   3 four scales, crop 256, batch 6, --blotch 0.2 --cold 0.25 (blended with 1 at t = 0.1 as the
#     committed weights were)
# then the held-out evaluation at 1080p of all of them and the blend beside the committed weights.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
export GPUS=4
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16
cp passes/src/denoise/neural/lucid-rae-v3.safetensors /tmp/committed.safetensors
LUCID=/tmp/bin/lucid SHARDS=16 SEED_OFFSET=16 ROOMS=24 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-12:::$W+scales=4+crop=128+batch=24 kernel:l1gradflip:0-12:::$W+scales=4+crop=256+batch=6 kernel:l1gradflip:0-12:::$W+scales=5+crop=256+batch=6 kernel:l1gradflip:0-12:::$W+scales=4+crop=256+batch=6+blotch=0.2+cold=0.25" \
  INIT=/tmp/committed.safetensors MINUTES=${MINUTES:-9} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  short=$(basename "$f" | sed -e 's/.*widths_16_32_64_64_32_16_//')
  cp "$f" "/tmp/w-$short"; cp "${f%.safetensors}.json" "/tmp/out/${short%.safetensors}.json"
done
cp /tmp/train-out/compare.json /tmp/out/
(cd training && python3 blend.py /tmp/w-scales_4_crop_256_batch_6.safetensors \
  /tmp/w-scales_4_crop_256_batch_6_blotch_0.2_cold_0.25.safetensors --t 0.1 --out /tmp/w-blend256.safetensors)
tar czf /tmp/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors)
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="$(cd /tmp && ls /tmp/w-*.safetensors | tr '\n' ' ')" \
  training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo JOB-END
