#!/usr/bin/env bash
# Thirty-seventh session, run in the thirty-eighth (one H200, 1,235 s; results beside this file and in training/README.md). The
# committed weights are since that session a blend, half and half, of the weights before them and
# their fine-tuning with training windows that reach 32 frames (runs/v31-long-windows: `long`
# alone lost `classroom`, the blend kept it and took `long`'s gains on `caustics`). Does a second
# round gain again, and is it the blotch term that costs `classroom`? Three 4.5-minute
# fine-tunings of the committed weights at once on a fresh dataset (4 shards, SEED_OFFSET 112,
# three sequences in ten coming to rest), all with windows that reach 32 frames:
#   again     runs/v31's `long` once more: burn-in 0-24, 8 frames with a loss, the blotch term 0.2
#             beyond a 0.3 margin, a quarter of the windows cold
#   plain     the same without the blotch term and the cold windows
#   frames12  as `again`, with burn-in 0-20 and 12 frames with a loss
# then each blended half and half with the committed weights (blend.py), and all six held out over
# 30 frames (`caustics`, then `classroom`, with `--maps`) beside the committed weights. First, the
# committed weights' parity test under the validation layer on both inference paths and their time
# at 1080p (bench/neural_ab_gpu.sh, one round: .gpu/neural_parity.xz and .gpu/layers.tar.xz from
# bench/pack_parity.sh): the blend of the thirty-seventh session has not yet run on tensor cores.
# Writes into /tmp/out: ab/ (the parity log and the time), compare.json, <variant>.json,
# weights.tgz (w-<variant>.safetensors), then the metrics, summary and by_brightness per scene,
# over the 30 frames and over their first 20 as a 20-frame sequence (FIRST=20); job_gpu.sh brings
# them back as one out.tgz once they are more than a command returns. Start and wait with
# training/job_gpu.sh (README, Commands):
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v32-long-again/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait
# About 20 s for the parity test and the time, 530 s to render and train (runs/v31: 527 s) and
# 760 s to evaluate (runs/v31's six extra weights: 715 s; the first 20 frames evaluated again,
# about 20 s a scene). .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo /tmp/w-*.safetensors /tmp/b-*.safetensors && cp -r . /tmp/repo && cd /tmp/repo
committed=passes/src/denoise/neural/lucid-rae-v3.safetensors
P=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-4
W=$P+cold=0.25+blotch-margin=0.3+blotch=0.2
echo "START $(date +%s)"
ROUNDS=1 SIZES=1920x1080 bench/neural_ab_gpu.sh /tmp/out/ab lucid
echo "PARITY-END $? $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=112 STOPS=0.3 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-24:::$W kernel:l1gradflip:0-24:::$P kernel:l1gradflip:0-20:::$W+frames=12" \
  INIT="$committed" MINUTES=${MINUTES:-4.5} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
for n in $(training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out \
  '*frames_12*=frames12' '*blotch_0.2*=again' '*=plain'); do
  (cd training && python3 blend.py "../$committed" "/tmp/w-$n.safetensors" --t 0.5 --out "/tmp/b-$n.safetensors")
done
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors)
echo "EVAL-START $(date +%s)"
rm -rf /tmp/heldout-*
FRAMES=30 FIRST=20 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO="$(echo /tmp/w-*.safetensors /tmp/b-*.safetensors)" \
  training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
