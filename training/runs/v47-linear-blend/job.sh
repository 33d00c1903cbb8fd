#!/usr/bin/env bash
# Run once, at f240567 (whose model.py and study_compare.py have the linear blend; removed after it:
# training/README.md, "The history blended in linear space").
# Forty-sixth session (one H200). On the held-out `caustics` path the learned denoiser's FLIP
# rises 7% from frames 2-4 to frames 12 on (0.0162 to 0.0173, runs/v45) while the per-frame spatial
# filter's stays flat (content of equal difficulty) and SVGF's falls: error that grows with the
# history. The output blends with its warped history in log space, an exponential moving average
# of log(1 + radiance): its mean is the mean of the logs, below the log of the mean by an amount
# set by how noisy each frame's prediction is (Jensen), which training compensates only for the
# noise it saw. Blending in linear space has no such bias. A probe without training: the committed
# weights on runs/v44's held-out study (512x512, 3 sequences of 30 frames a scene, 1024 samples,
# in PyTorch), with the log blend they were trained with and with the linear one.
#   source .gpu/env.sh && training/runs/v47-linear-blend/job.sh
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
COMMITTED=passes/src/denoise/neural/lucid-rae-v3.safetensors
echo "START $(date +%s)"
/tmp/bin/lucid dataset --scenes classroom,caustics --size 512x512 --frames 30 --sequences 3 \
  --reference-spp 1024 --out /tmp/study > /dev/null
echo "DATA-END $? $(date +%s)"
(cd training && python3 study_compare.py --data /tmp/study ../$COMMITTED --out $OUT/study-log.json &&
  python3 study_compare.py --data /tmp/study ../$COMMITTED --linear-blend --out $OUT/study-linear.json)
echo "STUDY-END $? $(date +%s)"
