#!/usr/bin/env bash
# Thirty-ninth session, for the next session's device time (one H200; not yet run). Three questions:
# 1. runs/v33's `spatial4` blend held out on both scenes (runs/v33-spatial-variance/eval.sh's
#    work: it tied the committed weights on `classroom` over 20 frames; alone it has the best
#    `caustics` yet). Ship it if it beats the committed weights' `caustics` without losing
#    `classroom`.
# 2. The first frames after a reset filtered further (training/cold_filter_study.py: a-trous steps
#    over the learned denoiser's output, edge-stopped by normals and luminance, blended in over the
#    first K frames; with --oracle 16 also the bound of a choice per 16x16 block of where to
#    filter), on the 30-frame run's held-out frames, evaluated over their first 8. On
#    lavapipe (`classroom`, frame 0) it gains 3% of FLIP at 320x180, 6.6% at 640x360 and 8.8% at
#    1280x720 (the learned denoiser under-filters the cold frames there, the more so the larger
#    the frame) but costs `caustics` 12% at 640x360, and the block oracle keeps the gain without
#    the loss: how much each way at 1080p? Needs the
#    OpenEXR wheel for the machine's Python 3.12 in .gpu/wheels (`pip download --no-deps
#    --only-binary=:all: --python-version 3.12 --platform manylinux2014_x86_64 -d .gpu/wheels
#    OpenEXR`) unless OpenEXR imports there.
# 3. Weights for the first frames after a reset alone. Held out at 1080p the learned denoiser's
#    FLIP is 1.075x SVGF's at frame 0 of `classroom`, 0.96x at frame 3, 0.70x warmed up; every
#    fine-tuning since the blend made frame 0 no better (runs/v34: larger rooms made it worse). The
#    committed weights serve both regimes, and a quarter of their training windows start cold.
#    Here four 3.25-minute fine-tunings of the committed weights on cold windows only (burn-in 0,
#    every window starting without history, its frames weighed alike, runs/v32's `again` recipe
#    otherwise) on a fresh dataset (4 shards of 512x512, SEED_OFFSET 160):
#      cold4   4 frames with a loss: weights for frames 0-3
#      cold8   8 frames with a loss: weights for frames 0-7
#      cold4s  as cold4, with --spatial-variance-frames 4
#      cold4w  as cold4, with a fifth kernel scale (widened from nothing, as runs/v34's large5):
#              more reach, for the cold frames that lack it (question 2)
#    each also blended half and half with the committed weights (b-; cold4w's with the committed
#    weights widened alike by widen_scales.py), all held out over the first
#    10 frames of both scenes. A renderer that switched weights at frame K after a reset would show
#    the cold run's frames 0..K-1 exactly (the cold weights see only their own history there) and
#    the committed weights' later frames nearly (those then start from the cold weights' output):
#    if frames 0-3 gain enough to move the 30-frame mean, the switch is worth building.
# First the parity test under the validation layer on both inference paths (nine fixtures) and the
# denoiser's time at 1080p (bench/neural_ab_gpu.sh, one round; run bench/pack_parity.sh before
# carrying .gpu). Writes into /tmp/out: ab/, the 30-frame metrics, summary and by_brightness per
# scene (b-spatial4 beside the committed weights), cold_filter_<scene>.csv, cold/ (the 10-frame
# metrics of the cold weights), compare.json,
# <variant>.json and weights.tgz (w- and b-<variant>.safetensors); job_gpu.sh brings them back as
# one out.tgz. Start and wait:
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v35-cold-start/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait
# About 10 s for the parity test, 390 s for the 30-frame evaluation (runs/v34's: 321 s and 66 s a
# weights file), about 150 s for the filter study (10 x 2 filtered folders, 8 frames of 15 methods
# evaluated a scene), 180 s to render the dataset, 225 s to train and blend, 280 s for the
# 10-frame evaluation (eight weights files): some 1,250 s.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
rm -rf /tmp/out /tmp/v33 /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out /tmp/v33
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo /tmp/w-*.safetensors /tmp/b-*.safetensors && cp -r . /tmp/repo && cd /tmp/repo
committed=passes/src/denoise/neural/lucid-rae-v3.safetensors
tar xzf training/runs/v33-spatial-variance/weights.tgz -C /tmp/v33
C=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-4+cold=1+blotch-margin=0.3+blotch=0.2
echo "START $(date +%s)"
ROUNDS=1 SIZES=1920x1080 bench/neural_ab_gpu.sh /tmp/out/ab lucid
echo "PARITY-END $? $(date +%s)"
FRAMES=30 FIRST=20 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO=/tmp/v33/b-spatial4.safetensors training/evaluate_gpu.sh /tmp/out
echo "EVAL-SPATIAL-END $? $(date +%s)"
mkdir -p /tmp/pylib
python3 -c "import OpenEXR" 2>/dev/null || pip install --no-index --no-deps --target /tmp/pylib .gpu/wheels/openexr-*.whl
for scene in caustics classroom; do
  (cd training && PYTHONPATH=/tmp/pylib python3 cold_filter_study.py "/tmp/heldout-$scene" --oracle 16 \
    4,8:0.1:2 4,8,16:0.1:2 4,8,16:0.1:4 8,16:0.1:4 4,8,16:0.15:6)
  /tmp/bin/lucid evaluate "/tmp/heldout-$scene" --frames 8
  cp "/tmp/heldout-$scene/first-8/metrics.csv" "/tmp/out/cold_filter_$scene.csv"
done
echo "COLD-FILTER-END $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=160 STOPS=0.3 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0:::$C+frames=4 kernel:l1gradflip:0:::$C+frames=8 kernel:l1gradflip:0:::$C+frames=4+spatial-variance-frames=4 kernel:l1gradflip:0:::$C+frames=4+scales=5" \
  INIT="$committed" MINUTES=${MINUTES:-3.25} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
(cd training && python3 widen_scales.py "../$committed" --scales 5 --out /tmp/committed-5.safetensors)
for n in $(training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out \
  '*scales_5*=cold4w' '*spatial-variance-frames_4*=cold4s' '*frames_8*=cold8' '*frames_4*=cold4'); do
  base="../$committed"
  if [ "$n" = cold4w ]; then base=/tmp/committed-5.safetensors; fi
  (cd training && python3 blend.py "/tmp/w-$n.safetensors" "$base" --t 0.5 --out "/tmp/b-$n.safetensors")
done
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp $(cd /tmp && ls w-cold*.safetensors b-cold*.safetensors)
echo "EVAL-COLD-START $(date +%s)"
rm -rf /tmp/heldout-*
FRAMES=10 BENCH=0 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO="$(echo /tmp/w-cold*.safetensors /tmp/b-cold*.safetensors)" training/evaluate_gpu.sh /tmp/out/cold
echo "EVAL-COLD-END $? $(date +%s)"
echo JOB-END
