#!/usr/bin/env bash
# Thirty-second session (one H200): the learned denoiser with a firefly clamp on its input sample
# (experiment binary, the headroom read from the weights' `firefly_headroom` metadata), at headrooms
# 16, 64 and 256, beside the committed weights (no clamp), on the held-out paths at 1080p; then
# `lucid evaluate --maps` on `caustics` for where each method flickers (by_brightness.csv).
# .gpu/lucid.xz: the release lucid binary of 2e5a990 with experiment.patch applied (the clamp in
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
for headroom in (16, 64, 256):
    save_file(load_file(src), f"/tmp/variants/clamp{headroom}.safetensors",
              metadata={**metadata, "firefly_headroom": str(headroom)})
PY
run=/tmp/variants
echo "HELDOUT-START $(date +%s)"
SCENES="caustics classroom" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="$run/clamp16.safetensors $run/clamp64.safetensors $run/clamp256.safetensors" \
  training/evaluate_gpu.sh /tmp/eval
echo "HELDOUT-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
/tmp/bin/lucid evaluate /tmp/heldout-caustics --maps > /dev/null
cp /tmp/heldout-caustics/maps/by_brightness.csv /tmp/out/by_brightness_caustics.csv
echo "MAPS-END $(date +%s)"
echo JOB-END
