#!/usr/bin/env bash
# Forty-third session, for the next session's device time (one H200; not yet run). runs/v41 found
# the committed network's history weight and gate where the held-out scenes would put them: the
# warmed-up state, not the blend, is what 0.7x SVGF's FLIP needs 10% more of. The network's memory
# of past frames is its output, the running means and the averaged surface, all fixed in meaning;
# this gives it state of its own (train.py --recurrent 8: 8 channels at full resolution that a
# layer on dec0's features writes, warped with the output's history, and enc0 reads in the next
# frame; on the tensor-core path enc0's 24 inputs are padded to 32 already). Two variants side by
# side from the committed weights on runs/v39's dataset recipe (SEED_OFFSET 176), the same windows:
# `control` (the whole network fine-tuned) and `recurrent` (the same with the state, enc0's
# weights for it at zero and its layer afresh), 4 minutes at lr 1e-3. The renderer does not run
# recurrent state yet: the question is the validation rooms' FLIP and temporal instability
# against the control (compare.json), then the held-out scenes' through PyTorch (study.json:
# `lucid dataset --scenes classroom,caustics`, 3 sequences of 30 frames each at 512x512 against
# 1024 samples, and study_compare.py over the committed weights and both variants); only a clear
# gain on both is worth the shaders.
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v42-recurrent-state/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait      (if the first command ran out first)
# About 100 s for the dataset, 240 s to train, 40 s to export, 120 s for the held-out study:
# some 510 s.
# .gpu/lucid.xz: a release lucid binary (the dataset's renderer).
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=256+batch=4+lr=1e-3+cold=0.25+blotch-margin=0.3+blotch=0.2
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=2 SEED_OFFSET=176 STOPS=0.3 SIZE=512x512 SIZE_FIRST=256x256 ROOMS=6 ROOMS_FIRST=0 \
  FRAMES=32 SEQUENCES=1 VARIANTS="kernel:l1gradflip:0-24:::$W kernel:l1gradflip:0-24:::$W+recurrent=8" \
  INIT=passes/src/denoise/neural/lucid-rae-v3.safetensors MINUTES=${MINUTES:-4} TRAIN_ARGS="--val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*recurrent_8*=recurrent' '*=control'
cp /tmp/train-out/compare.json /tmp/out/compare.json
tar czf /tmp/out/weights.tgz -C /tmp w-control.safetensors w-recurrent.safetensors
/tmp/bin/lucid dataset --scenes classroom,caustics --size 512x512 --frames 30 --sequences 3 \
  --reference-spp 1024 --out /tmp/study
(cd training && python3 study_compare.py --data /tmp/study ../passes/src/denoise/neural/lucid-rae-v3.safetensors \
  /tmp/w-control.safetensors /tmp/w-recurrent.safetensors --out /tmp/out/study.json)
echo "STUDY-END $? $(date +%s)"
echo JOB-END
