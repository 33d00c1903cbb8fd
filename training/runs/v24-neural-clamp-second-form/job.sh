#!/usr/bin/env bash
# Thirty-third session (one H200): the learned denoiser with a firefly clamp on its input sample in
# the form SVGF's took in the thirty-second session (the bound from this frame's neighbours is the
# *second* brightest neighbour; the thirty-second session's experiment took the brightest,
# ../v22-neural-firefly-clamp/), at headrooms 32, 64 and 256, beside the committed weights (no
# clamp), on the held-out paths at 1080p; then `lucid evaluate --maps` on `caustics`
# (by_brightness_caustics.csv).
# .gpu/lucid.xz: the release lucid binary of 52b0d2c with experiment.patch applied (the clamp in
# features.comp, its headroom from the weights' `firefly_headroom` metadata, 0 = off); the variants
# are the committed weights with that metadata set.
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
mkdir -p /tmp/variants
python3 - <<'PY'
from safetensors import safe_open
from safetensors.torch import load_file, save_file
src = "passes/src/denoise/neural/lucid-rae-v3.safetensors"
metadata = safe_open(src, "pt").metadata()
for headroom in (32, 64, 256):
    save_file(load_file(src), f"/tmp/variants/clamp{headroom}.safetensors",
              metadata={**metadata, "firefly_headroom": str(headroom)})
PY
run=/tmp/variants
echo "HELDOUT-START $(date +%s)"
SCENES="caustics classroom" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="$run/clamp32.safetensors $run/clamp64.safetensors $run/clamp256.safetensors" \
  training/evaluate_gpu.sh /tmp/eval
echo "HELDOUT-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
/tmp/bin/lucid evaluate /tmp/heldout-caustics --maps > /dev/null
cp /tmp/heldout-caustics/maps/by_brightness.csv /tmp/out/by_brightness_caustics.csv
echo "MAPS-END $(date +%s)"
echo JOB-END
