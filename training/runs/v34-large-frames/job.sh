#!/usr/bin/env bash
# Thirty-eighth session, run in the thirty-ninth (one H200, 1,435 s; training/README.md has the results). Two questions
# in one job, each from what the thirty-eighth session measured:
# 1. runs/v33-spatial-variance held out: the variance inputs over the neighbourhood in the first
#    frames (w-control and w-spatial4 from its weights.tgz; no gain on lavapipe at 320x180).
# 2. Training rooms rendered at the held-out frames' scale. The learned denoiser's FLIP is 1.08x
#    SVGF's at frame 0 of `classroom` at 1080p but 0.91x at 320x180 (runs/v33's lavapipe look):
#    the first frames, where spatial filtering carries the output, are the worse the more pixels
#    a surface covers. The training rooms are 512x512 (every step to larger frames gained:
#    twenty-sixth and twenty-eighth sessions), and a fifth kernel scale trained on 256x256 and
#    512x512 frames was left unused (twenty-fourth and twenty-eighth sessions). Here the training
#    rooms are 1024x1024 (shards 1-3, 3 rooms each, SEED_OFFSET 144, three sequences in ten coming
#    to rest), shard 0's built-in scenes and validation rooms stay 512x512 (SIZE_FIRST), crops of
#    368 as before; two 4.5-minute fine-tunings of the committed weights with runs/v32's `again`
#    recipe: four scales (`large4`) and five (`large5`, the fifth widened as train.py's
#    load_weights starts it), each blended half and half with the committed weights (for five
#    scales, the committed weights widened alike by widen_scales.py).
# First the parity test under the validation layer on both inference paths (nine fixtures) and the
# denoiser's time at 1080p (bench/neural_ab_gpu.sh, one round; run bench/pack_parity.sh before
# carrying .gpu). Then everything held out over 30 frames and their first 20 (`caustics`, then
# `classroom`, `--maps`) beside the committed weights. Writes into /tmp/out: ab/, compare.json,
# <variant>.json, weights.tgz (w- and b-<variant>.safetensors), then the metrics, summary and
# by_brightness per scene; job_gpu.sh brings them back as one out.tgz. Start and wait:
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v34-large-frames/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait
# About 30 s for the parity test, 350 s to render (an estimate: twice runs/v33's pixels, which
# took 177 s), 300 s to train and blend, 720 s to evaluate (six weights files): some 1,400 s.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out /tmp/v33 && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo /tmp/w-*.safetensors /tmp/b-*.safetensors && cp -r . /tmp/repo && cd /tmp/repo
committed=passes/src/denoise/neural/lucid-rae-v3.safetensors
tar xzf training/runs/v33-spatial-variance/weights.tgz -C /tmp/v33
W=fireflies=5e-5+widths=16,32,64,64,32,16+crop=368+batch=4+lr=5e-4+cold=0.25+blotch-margin=0.3+blotch=0.2
echo "START $(date +%s)"
ROUNDS=1 SIZES=1920x1080 bench/neural_ab_gpu.sh /tmp/out/ab lucid lucid:/tmp/v33/b-spatial4.safetensors
echo "PARITY-END $? $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=144 STOPS=0.3 SIZE=1024x1024 SIZE_FIRST=512x512 ROOMS=3 ROOMS_FIRST=0 \
  FRAMES=32 SEQUENCES=1 VARIANTS="kernel:l1gradflip:0-24:::$W+scales=4 kernel:l1gradflip:0-24:::$W+scales=5" \
  INIT="$committed" MINUTES=${MINUTES:-4.5} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
(cd training && python3 widen_scales.py "../$committed" --scales 5 --out /tmp/committed-5.safetensors)
for n in $(training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*scales_5*=large5' '*scales_4*=large4'); do
  base="../$committed"
  if [ "$n" = large5 ]; then base=/tmp/committed-5.safetensors; fi
  (cd training && python3 blend.py "/tmp/w-$n.safetensors" "$base" --t 0.5 --out "/tmp/b-$n.safetensors")
done
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp $(cd /tmp && ls w-large*.safetensors b-large*.safetensors)
echo "EVAL-START $(date +%s)"
rm -rf /tmp/heldout-*
FRAMES=30 FIRST=20 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO="$(echo /tmp/v33/w-control.safetensors /tmp/v33/w-spatial4.safetensors /tmp/w-large*.safetensors /tmp/b-large*.safetensors)" \
  training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
