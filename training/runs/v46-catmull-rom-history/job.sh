#!/usr/bin/env bash
# Run once, at 331310c (whose train.py and study_compare.py have --history-warp; removed after it
# changed nothing: training/README.md, "The history resampled with the Catmull-Rom kernel").
# Forty-sixth session (one H200). Every frame the network blends its output with last frame's,
# reprojected by bilinear taps (model.warp_history, as the shaders do); most reprojections land
# near half-pixel offsets, where bilinear taps are a [1/2 1/2] blur, so a history carried for n
# frames is blurred n times and the network must trust it less where detail matters. The
# Catmull-Rom kernel (16 taps, used where all 16 are kept, clamped to the bilinear taps' range)
# keeps the detail. Measured in PyTorch on the held-out scenes (study.json-like, as runs/v44:
# 512x512, 3 sequences of 30 frames against 1024 samples):
#   1. the committed weights with each `history_warp` (bilinear, output, means), untrained for it;
#   2. runs/v44's recipe (dataset SEED_OFFSET 176, the same windows, 4 minutes at lr 1e-3 from the
#      committed weights) with --history-warp output and means, beside runs/v44's `control`
#      (the same recipe, bilinear), each also blended half and half with the committed weights.
#   source .gpu/env.sh && WAIT_S=540 training/job_gpu.sh start training/runs/v46-catmull-rom-history/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait      (if the first command ran out first)
# About 100 s for each dataset, 240 s to train, 40 s to export, 150 s for the studies.
# .gpu/lucid.xz: a release lucid binary (the dataset's renderer; main at 64143fb or later).
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=256+batch=4+lr=1e-3+cold=0.25+blotch-margin=0.3+blotch=0.2
COMMITTED=passes/src/denoise/neural/lucid-rae-v3.safetensors
CONTROL=training/runs/v44-motion-inputs/out/w-control.safetensors
echo "START $(date +%s)"
/tmp/bin/lucid dataset --scenes classroom,caustics --size 512x512 --frames 30 --sequences 3 \
  --reference-spp 1024 --out /tmp/study
for warp in bilinear output means; do
  (cd training && python3 study_compare.py --data /tmp/study ../$COMMITTED --history-warp $warp \
    --out /tmp/out/study-committed-$warp.json)
done
echo "STUDY-COMMITTED-END $? $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=2 SEED_OFFSET=176 STOPS=0.3 SIZE=512x512 SIZE_FIRST=256x256 ROOMS=6 ROOMS_FIRST=0 \
  FRAMES=32 SEQUENCES=1 VARIANTS="kernel:l1gradflip:0-24:::$W+history-warp=output kernel:l1gradflip:0-24:::$W+history-warp=means" \
  INIT=$COMMITTED MINUTES=${MINUTES:-4} TRAIN_ARGS="--val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*warp_output*=output' '*warp_means*=means'
cp /tmp/train-out/compare.json /tmp/out/compare.json
tar czf /tmp/out/weights.tgz -C /tmp w-output.safetensors w-means.safetensors
(cd training && python3 study_compare.py --data /tmp/study ../$COMMITTED ../$CONTROL --history-warp bilinear \
  --out /tmp/out/study-bilinear.json)
for warp in output means; do
  (cd training && python3 blend.py ../$COMMITTED /tmp/w-$warp.safetensors --t 0.5 --out /tmp/w-$warp-blend.safetensors &&
    python3 study_compare.py --data /tmp/study ../$COMMITTED /tmp/w-$warp.safetensors /tmp/w-$warp-blend.safetensors \
      --history-warp $warp --out /tmp/out/study-$warp.json)
done
echo "STUDY-END $? $(date +%s)"
echo JOB-END
