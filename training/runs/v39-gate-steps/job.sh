#!/usr/bin/env bash
# Forty-second session (one H200, the device seconds left after runs/v38; out/): the gate
# trained alone as runs/v37 trained the shipped one (steps 8 and 16 px), with the filter's two
# steps at other spacings, which cost the same: `s4-8` (less reach: what spreads a caustic's bright
# pixels less) and `s16-32` (more: the ordinary surfaces' residual noise, three quarters of the
# FLIP). runs/v38 held the shipped gate out over 30 frames (`classroom` FLIP 0.764x SVGF's,
# `caustics` 0.758x, 0.742x without the gate) and found that training it longer moves along the
# same trade. Both from the weights without the gate (98fc622's, .gpu/ungated.safetensors), at
# once on one GPU, runs/v37's recipe and dataset (2 shards, SEED_OFFSET 176, crops of 256), then
# held out at 1080p over 16 frames beside the shipped weights. Writes into /tmp/out: compare.json,
# s4-8.json, s16-32.json, weights.tgz and metrics_<scene>.csv.
#   source .gpu/env.sh && WAIT_S=520 training/job_gpu.sh start training/runs/v39-gate-steps/job.sh
# About 100 s for the dataset, 90 s to train, 20 s to export, 250 s to evaluate: some 460 s.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
rm -rf /tmp/out /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo /tmp/w-*.safetensors && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=256+batch=4+lr=5e-3+cold=0.25+blotch-margin=0.3+blotch=0.2
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=2 SEED_OFFSET=176 STOPS=0.3 SIZE=512x512 SIZE_FIRST=256x256 ROOMS=6 ROOMS_FIRST=0 \
  FRAMES=32 SEQUENCES=1 VARIANTS="kernel:l1gradflip:0-24:::$W+atrous-steps=4,8 kernel:l1gradflip:0-24:::$W+atrous-steps=16,32" \
  INIT=.gpu/ungated.safetensors MINUTES=${MINUTES:-1.5} TRAIN_ARGS="--gate-only --val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*atrous-steps_4_8*=s4-8' '*atrous-steps_16_32*=s16-32'
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp w-s4-8.safetensors w-s16-32.safetensors
echo "EVAL-START $(date +%s)"
FRAMES=16 BENCH=0 MAPS=0 OIDN=0 SCENES="classroom caustics" LUCID=/tmp/bin/lucid \
  ALSO="/tmp/w-s4-8.safetensors /tmp/w-s16-32.safetensors" training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
