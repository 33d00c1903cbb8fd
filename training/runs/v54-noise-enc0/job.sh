#!/usr/bin/env bash
# Forty-ninth session (one H200), after runs/v53: there the two inputs of the running means' own
# noise (train.py --noise-inputs) beat their control on both held-out scenes in PyTorch (FLIP
# 0.989x against 0.994x the committed weights' on `caustics`, 1.057x against 1.081x on
# `classroom`), but fine-tuning the whole network drifted worse on `classroom`, with or without
# them, and blended half and half with the committed weights neither won on both. Here only `enc0`,
# the layer that reads the inputs, is fine-tuned (--train-layers enc0), so the rest of the network
# stays the committed one: `control` (enc0 alone) and `noise` (enc0 alone, with the inputs), each
# also blended half and half with the committed weights, on runs/v53's recipe, dataset and
# held-out study.
#   source .gpu/env.sh && WAIT_S=540 training/job_gpu.sh start training/runs/v54-noise-enc0/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait      (if the first command ran out first)
# .gpu/lucid49.xz: a release lucid binary (the dataset's renderer; main at ef9dcac): xz -c target/release/lucid.
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid49.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=256+batch=4+lr=1e-3+cold=0.25+blotch-margin=0.3+blotch=0.2
COMMITTED=passes/src/denoise/neural/lucid-rae-v3.safetensors
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=2 SEED_OFFSET=176 STOPS=0.3 SIZE=512x512 SIZE_FIRST=256x256 ROOMS=6 ROOMS_FIRST=0 \
  FRAMES=32 SEQUENCES=1 VARIANTS="kernel:l1gradflip:0-24:::$W+train-layers=enc0 kernel:l1gradflip:0-24:::$W+train-layers=enc0+noise-inputs=" \
  INIT=$COMMITTED MINUTES=${MINUTES:-4} TRAIN_ARGS="--val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*noise*=noise' '*=control'
for v in control noise; do
  (cd training && python3 blend.py ../$COMMITTED /tmp/w-$v.safetensors --t 0.5 --out /tmp/w-$v-blend.safetensors)
done
cp /tmp/train-out/compare.json /tmp/out/compare.json
tar czf /tmp/out/weights.tgz -C /tmp w-control.safetensors w-noise.safetensors
/tmp/bin/lucid dataset --scenes classroom,caustics --size 512x512 --frames 30 --sequences 3 \
  --reference-spp 1024 --out /tmp/study
(cd training && python3 study_compare.py --data /tmp/study ../$COMMITTED /tmp/w-control.safetensors \
  /tmp/w-noise.safetensors /tmp/w-control-blend.safetensors /tmp/w-noise-blend.safetensors --out /tmp/out/study.json)
echo "STUDY-END $? $(date +%s)"
echo JOB-END
