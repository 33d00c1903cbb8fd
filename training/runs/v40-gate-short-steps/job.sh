#!/usr/bin/env bash
# Forty-second session, for the next session's device time (one H200; run in the forty-third session, training/README.md). runs/v39 found
# the gate trained alone better with the filter's steps at 4 and 8 pixels than at 8 and 16, and
# worse at 16 and 32 (held out over 16 frames; shipped). Here:
#   1. the gate trained alone as in runs/v39 (from the weights without it, .gpu/ungated.safetensors;
#      runs/v37's recipe and dataset) with shorter steps still: `s2-4`, and three steps `s2-4-8`
#      (one step more, about 0.1 ms: 1.98 ms at 1080p if each costs what runs/v39's did);
#   2. the output heads trained alone (train.py --train-layers) from the committed weights, on the
#      same data, 3 minutes at lr 5e-4: `out` (the full resolution's kernels, blend and gate) and
#      `heads` (the four scales' heads). The whole network fine-tuned drifted on `caustics`
#      (runs/v36); the gate alone did not, and the heads are the next smallest part to train;
#   3. the time of the gates against the committed weights' at 1080p (ab/, one round, after the
#      parity test);
#   4. the committed weights (steps 4 and 8) held out over 30 frames and their first 16 with the
#      maps (the light kept by brightness) beside the forty-first session's gate (steps 8 and 16,
#      .gpu/gated-8-16.safetensors, runs/v38's 30-frame figures) and the four trainings.
# Writes into /tmp/out: gates.json and heads-compare.json (compare_gpu.sh's compare.json of each),
# s2-4.json, s2-4-8.json, out.json, heads.json, weights.tgz, ab/, and the metrics, summary and
# by_brightness per scene; job_gpu.sh brings them back as one out.tgz.
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v40-gate-short-steps/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait
# About 100 s for the dataset, 90 + 180 s to train, 40 s to export, 30 s for the parity test and
# the times, 321 s for the 30-frame evaluation and 66 s a weights file (five): some 1,090 s.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
rm -rf /tmp/out /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo /tmp/w-*.safetensors && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=256+batch=4+lr=5e-3+cold=0.25+blotch-margin=0.3+blotch=0.2
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=2 SEED_OFFSET=176 STOPS=0.3 SIZE=512x512 SIZE_FIRST=256x256 ROOMS=6 ROOMS_FIRST=0 \
  FRAMES=32 SEQUENCES=1 VARIANTS="kernel:l1gradflip:0-24:::$W+atrous-steps=2,4 kernel:l1gradflip:0-24:::$W+atrous-steps=2,4,8" \
  INIT=.gpu/ungated.safetensors MINUTES=${MINUTES:-1.5} TRAIN_ARGS="--gate-only --val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "GATES-END $? $(date +%s)"
training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*atrous-steps_2_4_8*=s2-4-8' '*atrous-steps_2_4*=s2-4'
cp /tmp/train-out/compare.json /tmp/out/gates.json
H=${W/lr=5e-3/lr=5e-4}
LUCID=/tmp/bin/lucid VARIANTS="kernel:l1gradflip:0-24:::$H+train-layers=out kernel:l1gradflip:0-24:::$H+train-layers=out,out_half,out_quarter,out_eighth" \
  INIT=passes/src/denoise/neural/lucid-rae-v3.safetensors MINUTES=${HEADS_MINUTES:-3} TRAIN_ARGS="--val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/heads-out
echo "HEADS-END $? $(date +%s)"
training/variant_weights.sh /tmp/heads-out/variants.tar.gz /tmp /tmp/out '*out_eighth*=heads' '*=out'
cp /tmp/heads-out/compare.json /tmp/out/heads-compare.json
tar czf /tmp/out/weights.tgz -C /tmp w-s2-4.safetensors w-s2-4-8.safetensors w-out.safetensors w-heads.safetensors
ROUNDS=1 SIZES=1920x1080 bench/neural_ab_gpu.sh /tmp/out/ab lucid lucid:/tmp/w-s2-4.safetensors lucid:/tmp/w-s2-4-8.safetensors
echo "AB-END $? $(date +%s)"
FRAMES=30 FIRST=16 BENCH=0 MAPS=1 OIDN=0 SCENES="classroom caustics" LUCID=/tmp/bin/lucid \
  ALSO="$PWD/.gpu/gated-8-16.safetensors /tmp/w-s2-4.safetensors /tmp/w-s2-4-8.safetensors /tmp/w-out.safetensors /tmp/w-heads.safetensors" \
  training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
