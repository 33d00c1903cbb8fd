#!/usr/bin/env bash
# Thirty-eighth session (one H200): the first frames after a reset. Held out, the learned denoiser
# is above SVGF's FLIP for its first three frames on `classroom` (1.08x at frame 0, 0.96x at frame
# 3; runs/v32-long-again), where its variance inputs are 0 (one sample) or taken over two or three
# samples, while SVGF estimates the variance over each pixel's neighbourhood for its first four
# frames. Weights whose `spatial_variance_frames` metadata is 4 take both variance inputs over the
# pixel's 3x3 neighbourhood of this frame's samples while the history is shorter than 4 frames
# (training/model.py, `features`; shaders/neural/features.comp). Two fine-tunings of the committed
# weights at once, runs/v32's `again` recipe (burn-in 0-24, 8 frames with a loss, the blotch term
# 0.2 beyond a 0.3 margin, a quarter of the windows cold), on a fresh dataset (4 shards,
# SEED_OFFSET 128, three sequences in ten coming to rest):
#   control   as the committed weights see their inputs
#   spatial4  with --spatial-variance-frames 4
# then each blended half and half with the committed weights (the variant as blend.py's A, so the
# blend keeps its metadata). Training only, to fit this session's device time; the held-out
# evaluation is runs/v33-spatial-variance/eval.sh. Writes into /tmp/out: compare.json,
# <variant>.json and weights.tgz (w-<variant> and b-<variant>.safetensors). Start and wait with
# training/job_gpu.sh:
#   source .gpu/env.sh && WAIT_S=440 training/job_gpu.sh start training/runs/v33-spatial-variance/job.sh
# About 190 s to render the dataset, MINUTES (3.25) to train, 30 s to export and blend.
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo /tmp/w-*.safetensors /tmp/b-*.safetensors && cp -r . /tmp/repo && cd /tmp/repo
committed=passes/src/denoise/neural/lucid-rae-v3.safetensors
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-4+cold=0.25+blotch-margin=0.3+blotch=0.2
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=128 STOPS=0.3 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-24:::$W kernel:l1gradflip:0-24:::$W+spatial-variance-frames=4" \
  INIT="$committed" MINUTES=${MINUTES:-3.25} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
for n in $(training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out \
  '*spatial-variance-frames_4*=spatial4' '*=control'); do
  (cd training && python3 blend.py "/tmp/w-$n.safetensors" "../$committed" --t 0.5 --out "/tmp/b-$n.safetensors")
done
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors b-*.safetensors)
echo JOB-END
