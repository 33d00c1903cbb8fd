#!/usr/bin/env bash
# Session 21 (training/runs/v12-finetune): fine-tunings of the committed blend (plain, --blotch 0.03, --blotch 0.06), then the
# held-out evaluation of all three beside the committed weights.
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4
SHARDS=4 ROOMS=24 FRAMES=32 SEQUENCES=1 LUCID=/tmp/bin/lucid \
  VARIANTS="kernel:l1gradflip:0-12:::$W kernel:l1gradflip:0-12:::$W+blotch=0.03 kernel:l1gradflip:0-12:::$W+blotch=0.06" \
  INIT=passes/src/denoise/neural/lucid-rae-v3.safetensors MINUTES=8 TRAIN_ARGS="--batch 24 --watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $?"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  b=$(basename "$f")
  short=$(echo "$b" | sed -e 's/kernel-l1gradflip-burn0-12-fireflies_5e-5_widths_16_32_64_64_32_16_//')
  cp "$f" "/tmp/out/$short"; cp "${f%.safetensors}.json" "/tmp/out/${short%.safetensors}.json"
done
cp /tmp/train-out/compare.json /tmp/out/
ls /tmp/out
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="$(ls /tmp/out/*.safetensors | tr '\n' ' ')" training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $?"
cp /tmp/eval/metrics_*.csv /tmp/out/
tar czf /tmp/out.tgz -C /tmp out
echo JOB-END
