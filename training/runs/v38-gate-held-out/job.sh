#!/usr/bin/env bash
# Forty-first session, run in the forty-second (one H200; out/, training/README.md): the shipped
# gate (runs/v37, trained alone on the committed weights for 72 s) held out as the weights before
# it were, and two longer gate-only trainings that might keep `caustics` where it was. runs/v37
# measured 16 frames without maps: `classroom` FLIP 0.0459 -> 0.0438 (every frame below SVGF's),
# `caustics` 0.01657 -> 0.01701. Here:
#   0. the parity test on both inference paths (bench/pack_parity.sh's .gpu/neural_parity.xz) and
#      an A/B of the gated filter's tile at 1080p, two rounds (ab/): .gpu/lucid-base.xz (3ed2cd5:
#      the tile's illumination float32, its normals vec3) against .gpu/lucid.xz (the illumination
#      in half precision, the normals three float arrays);
#   1. two gate-only trainings (train.py --gate-only) of the ungated weights the gate was added to
#      (98fc622's, carried as .gpu/ungated.safetensors), 4 minutes each at once on runs/v36's full
#      dataset (4 shards of 512x512, SEED_OFFSET 176, crops of 368: about 2.5x the steps and 4x
#      the rooms of runs/v37's): `long`, runs/v37's recipe, and `energy`, the same with --energy
#      10 (the light of 8x8 blocks against the reference's, what a filter that spreads a caustic
#      loses; runs/v29's weight);
#   2. the committed weights (gated) over 30 frames and their first 20 at 1080p on both scenes,
#      with the maps (the light kept by brightness: the gate filters the illumination, so a small
#      caustic could lose light), beside the ungated weights and the two trainings; and their time
#      on both inference paths from 640x360 to 1920x1080 (training/bench_gpu.sh:
#      neural_times.json), the table the issue asks for, last written in the twentieth session.
# Writes into /tmp/out: ab/, compare.json, long.json, energy.json, weights.tgz (w-long,
# w-energy), neural_times.json, and the metrics, summary and by_brightness per scene; job_gpu.sh
# brings them back as one out.tgz.
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v38-gate-held-out/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait
# About 60 s for the parity test and the A/B, 180 s for the dataset, 240 s to train and 60 s to
# export, 60 s for the times, 321 s for the 30-frame evaluation and 66 s a weights file (three):
# some 1,120 s.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
rm -rf /tmp/out /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo /tmp/w-*.safetensors && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-3+cold=0.25+blotch-margin=0.3+blotch=0.2+atrous-steps=8,16
echo "START $(date +%s)"
ROUNDS=2 SIZES=1920x1080 bench/neural_ab_gpu.sh /tmp/out/ab lucid-base lucid
echo "PARITY-END $? $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=176 STOPS=0.3 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-24:::$W kernel:l1gradflip:0-24:::$W+energy=10" \
  INIT=.gpu/ungated.safetensors MINUTES=${MINUTES:-4} TRAIN_ARGS="--gate-only --val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*energy_10*=energy' '*=long'
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp w-long.safetensors w-energy.safetensors
echo "EVAL-START $(date +%s)"
FRAMES=30 FIRST=20 BENCH=1 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO="$PWD/.gpu/ungated.safetensors /tmp/w-long.safetensors /tmp/w-energy.safetensors" \
  training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
