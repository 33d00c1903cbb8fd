#!/usr/bin/env bash
# Forty-sixth session (one H200): where the learned denoiser's error grows along the held-out
# `caustics` path. Its FLIP rises 7% from frames 2-4 to frames 12-29 (runs/v45) while the per-frame
# spatial filter's stays flat and SVGF's falls; neither a sharper history (runs/v46) nor a linear
# history blend (runs/v47) explains it. error_growth.py maps per-pixel FLIP over both windows, per
# method, and splits the change by the reference's brightness, by the samples' noise and by the
# method's bias. Beside the committed weights, the same weights with the running means capped at 8
# frames (`history_frames` metadata, set_metadata.py), which the thirty-seventh session found
# better on `caustics` and worse on `classroom`: whether the cap removes the rise says whether the
# running means' length carries it.
#   source .gpu/env.sh && training/runs/v48-error-growth/job.sh
set -u
mkdir -p /tmp/bin /tmp/pylib
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
python3 -c "import OpenEXR" 2>/dev/null || pip install -q --no-index --no-deps --target /tmp/pylib .gpu/wheels/openexr-*.whl
echo "START $(date +%s)"
(cd training && python3 set_metadata.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors history_frames=8 \
  --out /tmp/w-h8.safetensors)
rm -rf /tmp/heldout-caustics
/tmp/bin/lucid sequence --scene caustics --size 1920x1080 --frames 30 --reference-spp 1024 \
  --out /tmp/heldout-caustics --no-evaluate --also-neural-weights /tmp/w-h8.safetensors > /dev/null
echo "SEQUENCE-END $? $(date +%s)"
(cd training && PYTHONPATH=/tmp/pylib python3 error_growth.py /tmp/heldout-caustics \
  --methods neural neural-w-h8 svgf spatial --early 2 5 --late 12 30 --out "$OUT/growth")
echo "GROWTH-END $? $(date +%s)"
/tmp/bin/lucid evaluate /tmp/heldout-caustics > /dev/null && cp /tmp/heldout-caustics/metrics.csv "$OUT/metrics_caustics.csv"
echo "EVALUATE-END $? $(date +%s)"
