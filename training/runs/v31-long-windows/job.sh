#!/usr/bin/env bash
# Thirty-sixth session, run in the thirty-seventh on one H200 (training/README.md, "Training windows
# that reach 32 frames"). The thirtieth
# session's fine-tuning against blotches from the committed weights (the recipe runs/v22 and v29
# used, without the energy term) on a fresh dataset (4 shards, SEED_OFFSET 96) in which three
# sequences of ten slow down until the camera rests (`lucid dataset --stops 0.3`: the held-out
# `caustics` sway ends so, and the procedural paths never stop), three variants at once on the one
# GPU:
#   control  burn-in 0-12 and 8 frames with a loss: no pixel's running means pass 20 frames
#   long     burn-in 0-24: windows of up to 32 frames, so the running means reach their 32
#   capped   burn-in 0-12, trained with `--history-frames 12`
# then all three held out over 30 frames (`caustics`, then `classroom`), beside the committed weights
# with `history_frames` 8, 12 and 16 (`set_metadata.py`) on the same frames. Writes into /tmp/out:
# compare.json, <variant>.json, weights.tgz, then the held-out CSVs and summaries. Start and wait
# with training/job_gpu.sh (README, Commands):
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v31-long-windows/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait
# On a machine of two GPUs (nvidia-h200-x2, when lent) the variants and the two scenes spread over
# both (gpus.sh): the same device time does twice the work. On one H200, about 500 s to train
# (runs/v29's two variants took 492 s with the dataset) and 500 s to evaluate.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
committed=passes/src/denoise/neural/lucid-rae-v3.safetensors
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-4+cold=0.25+blotch-margin=0.3+blotch=0.2
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=96 STOPS=0.3 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-12:::$W kernel:l1gradflip:0-24:::$W kernel:l1gradflip:0-12:::$W+history-frames=12" \
  INIT="$committed" MINUTES=${MINUTES:-4.5} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  case "$f" in
    *burn0-24*) n=long ;;
    *history-frames_12*) n=capped ;;
    *) n=control ;;
  esac
  cp "$f" "/tmp/w-$n.safetensors"; cp "${f%.safetensors}.json" "/tmp/out/$n.json"
done
cp /tmp/train-out/compare.json /tmp/out/
tar czf /tmp/out/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors)
for h in 8 12 16; do
  (cd training && python3 set_metadata.py "../$committed" history_frames=$h --out "/tmp/h$h.safetensors")
done
echo "EVAL-START $(date +%s)"
rm -rf /tmp/heldout-*
FRAMES=30 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO="/tmp/w-control.safetensors /tmp/w-long.safetensors /tmp/w-capped.safetensors /tmp/h8.safetensors /tmp/h12.safetensors /tmp/h16.safetensors" \
  training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
echo JOB-END
