#!/usr/bin/env bash
# Prepared in session 23 for the next (4 GPUs, about 1250 s of device time after the start): 16
# dataset shards with fresh training rooms (SEED_OFFSET=16: shard 0 as before, shards 1-15 seeds
# 17-31), four 10-minute fine-tunings of the committed weights, one a GPU: four scales (the
# control) and five (the sixteenth, ddd56ac), each plain and with blotch 0.2 + cold 0.25; each
# pair's t = 0.1 blend; the held-out evaluation on GPUs 0-1 while GPU 2 times five scales against
# four at 1080p and GPU 3 A/Bs the path tracer's
# first hit in workgroup memory (branch first-hit-shared; .gpu/bins3.tar.xz: base = main's shaders,
# new = the branch's). .gpu/lucid.xz was built from c158933 (five scales included); rebuild it if HEAD has changed.
set -u
export GPUS=4
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W4=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4
W5=fireflies=5e-5+widths=16,32,64,64,32,16+scales=5
cp passes/src/denoise/neural/lucid-rae-v3.safetensors /tmp/committed.safetensors
LUCID=/tmp/bin/lucid SHARDS=16 SEED_OFFSET=16 ROOMS=24 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-12:::$W4 kernel:l1gradflip:0-12:::$W5 kernel:l1gradflip:0-12:::$W4+blotch=0.2+cold=0.25 kernel:l1gradflip:0-12:::$W5+blotch=0.2+cold=0.25" \
  INIT=/tmp/committed.safetensors MINUTES=10 TRAIN_ARGS="--batch 24 --watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  short=$(basename "$f" | sed -e 's/.*widths_16_32_64_64_32_16_//')
  cp "$f" "/tmp/w-$short"; cp "${f%.safetensors}.json" "/tmp/out/${short%.safetensors}.json"
done
cp /tmp/train-out/compare.json /tmp/out/
(cd training && for n in 4 5; do
  python3 blend.py /tmp/w-scales_$n.safetensors /tmp/w-scales_${n}_blotch_0.2_cold_0.25.safetensors --t 0.1 --out /tmp/w-blend$n.safetensors
done)
tar czf /tmp/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors)
tar czf /tmp/out.tgz -C /tmp out weights.tgz
(LUCID_DEVICE='#3' bash .gpu/ab_first_hit.sh > /tmp/out/ab_first_hit.txt 2>&1) &
ab=$!
# On GPU 2: the parity test under the validation layer on both paths (five scales included; its
# binary .gpu/neural_parity.xz, built from c158933; rebuild it if the fixtures change), then the five-scale network's time
# at 1080p and 854x480 on the tensor cores against four scales, alternately.
(LUCID_DEVICE='#2' SIZES="1920x1080 854x480" bench/neural_ab_gpu.sh /tmp/out/neural_ab \
  lucid:/tmp/committed.safetensors lucid:/tmp/w-blend5.safetensors > /tmp/out/neural_ab.log 2>&1) &
bench=$!
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="/tmp/w-scales_4.safetensors /tmp/w-scales_5.safetensors /tmp/w-blend4.safetensors /tmp/w-blend5.safetensors" \
  training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
wait $ab $bench
cp /tmp/eval/metrics_*.csv /tmp/out/
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo JOB-END
