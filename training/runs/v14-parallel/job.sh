#!/usr/bin/env bash
# Session 23, job B (4 GPUs): a data-parallel smoke test, the dataset (16 shards, glossy floors),
# two 9-minute fine-tunings of the v13 t = 0.1 blend, each data-parallel on two GPUs (plain;
# blotch 0.2 + cold 0.25), their t = 0.1 blend, and the held-out evaluation at 1080p.
set -u
export GPUS=4
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4
INIT=training/runs/v13-data/blend_t0.1.safetensors
# The data-parallel launcher on two GPUs, on a small dataset, while the real one renders.
(
  LUCID_DEVICE='#3' /tmp/bin/lucid dataset --out /tmp/ds-small --size 64x64 --frames 6 --rooms 4 --sequences 1 \
    --reference-spp 4 --seed 99 --validation-rooms 1 --no-builtin > /tmp/out/smoke.log 2>&1 &&
  cd training && CUDA_VISIBLE_DEVICES=2,3 python3 parallel.py 2 train.py --data /tmp/ds-small --minutes 0.2 --batch 4 \
    --frames 2 --burn-in 2 --crop 32 --model kernel --loss l1gradflip --widths 16,32,64,64,32,16 --scales 4 \
    --init "../$INIT" --out /tmp/smoke.safetensors --log /tmp/out/smoke.json --val-every 20 >> /tmp/out/smoke.log 2>&1
  echo "SMOKE-EXIT $?" >> /tmp/out/smoke.log
) &
smoke=$!
SHARDS=16 ROOMS=24 FRAMES=32 SEQUENCES=1 LUCID=/tmp/bin/lucid training/dataset_gpu.sh /tmp/lucid-dataset
echo "DATASET-END $(date +%s) $(du -sh /tmp/lucid-dataset | cut -f1)"
wait $smoke
tail -n 3 /tmp/out/smoke.log
if grep -q "SMOKE-EXIT 0" /tmp/out/smoke.log; then
  per=2
  VARIANTS="kernel:l1gradflip:0-12:::$W kernel:l1gradflip:0-12:::$W+blotch=0.2+cold=0.25"
else
  per=1
  VARIANTS="kernel:l1gradflip:0-12:::$W kernel:l1gradflip:0-12:::$W+blotch=0.2+cold=0.25 kernel:l1gradflip:0-12:1::$W kernel:l1gradflip:0-12:::$W+blotch=0.2+blotch-margin=0.3"
fi
echo "training $(date +%s) per=$per"
GPUS_PER_VARIANT=$per LUCID=/tmp/bin/lucid VARIANTS="$VARIANTS" INIT="$INIT" MINUTES=9 \
  TRAIN_ARGS="--batch 24 --watch covered-light" DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  b=$(basename "$f")
  short=$(echo "$b" | sed -e 's/kernel-l1gradflip-burn0-12-//' -e 's/fireflies_5e-5_widths_16_32_64_64_32_16_scales_4//')
  short=${short#_}; short=${short#-}; [ "$short" = ".safetensors" ] && short=plain.safetensors
  cp "$f" "/tmp/w-$short"; cp "${f%.safetensors}.json" "/tmp/out/${short%.safetensors}.json"
done
cp /tmp/train-out/compare.json /tmp/out/
ls /tmp/w-*
(cd training && python3 blend.py /tmp/w-plain.safetensors /tmp/w-blotch_0.2_cold_0.25.safetensors --t 0.1 --out /tmp/w-blend_t0.1.safetensors)
also="$INIT"
for w in /tmp/w-*.safetensors; do
  if python3 -c "import sys, torch; from safetensors.torch import load_file; sys.exit(0 if all(torch.isfinite(v).all() for v in load_file(sys.argv[1]).values()) else 1)" "$w"; then also="$also $w"; else echo "$w: non-finite, left out"; fi
done
tar czf /tmp/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors)
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo "EVAL-START $(date +%s) $also"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid ALSO="$also" training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo JOB-END
