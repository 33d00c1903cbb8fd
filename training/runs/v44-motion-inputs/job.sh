#!/usr/bin/env bash
# Forty-fifth session (one H200). The network does not know how its history was reprojected: how
# fast the view moves, and how much the bilinear resampling has softened the history it blends
# (every frame resamples it again, most at half-pixel offsets). On `caustics` its FLIP stays flat
# over the 30 frames while SVGF's falls 11% as the camera slows (runs/v40). train.py
# --motion-inputs gives enc0 two more inputs (model.motion_inputs: log(1 + the motion's length in
# pixels) and 2 (fx (1 - fx) + fy (1 - fy)) of its fractional offset), their weights at zero at
# the start, so the network starts as the committed one. Two variants side by side from the
# committed weights on runs/v42's recipe (dataset SEED_OFFSET 176, the same windows, 4 minutes at
# lr 1e-3): `control` (the whole network fine-tuned) and `motion` (the same with the inputs).
# Fine-tunings of the committed weights drift worse on the held-out scenes (runs/v42), so each is
# also blended half and half with the committed weights (blend.py; "model soup", as the committed
# weights are). The held-out scenes through PyTorch as in runs/v42 (study.json: `lucid dataset
# --scenes classroom,caustics`, 3 sequences of 30 frames at 512x512 against 1024 samples).
#   source .gpu/env.sh && WAIT_S=520 training/job_gpu.sh start training/runs/v44-motion-inputs/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait      (if the first command ran out first)
# About 100 s for the dataset, 240 s to train, 40 s to export, 150 s for the held-out study.
# .gpu/lucid-uexit.xz: a release lucid binary (the dataset's renderer; main at 64143fb).
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid-uexit.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=256+batch=4+lr=1e-3+cold=0.25+blotch-margin=0.3+blotch=0.2
COMMITTED=passes/src/denoise/neural/lucid-rae-v3.safetensors
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=2 SEED_OFFSET=176 STOPS=0.3 SIZE=512x512 SIZE_FIRST=256x256 ROOMS=6 ROOMS_FIRST=0 \
  FRAMES=32 SEQUENCES=1 VARIANTS="kernel:l1gradflip:0-24:::$W kernel:l1gradflip:0-24:::$W+motion-inputs=" \
  INIT=$COMMITTED MINUTES=${MINUTES:-4} TRAIN_ARGS="--val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*motion*=motion' '*=control'
for v in control motion; do
  (cd training && python3 blend.py ../$COMMITTED /tmp/w-$v.safetensors --t 0.5 --out /tmp/w-$v-blend.safetensors)
done
cp /tmp/train-out/compare.json /tmp/out/compare.json
tar czf /tmp/out/weights.tgz -C /tmp w-control.safetensors w-motion.safetensors
/tmp/bin/lucid dataset --scenes classroom,caustics --size 512x512 --frames 30 --sequences 3 \
  --reference-spp 1024 --out /tmp/study
(cd training && python3 study_compare.py --data /tmp/study ../$COMMITTED /tmp/w-control.safetensors \
  /tmp/w-motion.safetensors /tmp/w-control-blend.safetensors /tmp/w-motion-blend.safetensors --out /tmp/out/study.json)
echo "STUDY-END $? $(date +%s)"
echo JOB-END
