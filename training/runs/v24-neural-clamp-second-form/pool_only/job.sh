#!/usr/bin/env bash
# Thirty-third session (one H200): the clamp of ../job.sh on the radiance pooled for the kernels'
# coarser scales only (the full scale and the running means see the sample unclamped), at headrooms
# 16, 64 and 256 (written as -16, -64, -256: a negative headroom selects this variant), beside the
# committed weights, on the held-out `caustics` path at 1080p; then `lucid evaluate --maps`.
# .gpu/lucid.xz: the release lucid binary of 52b0d2c with experiment.patch applied (../job.sh's
# patch plus the negative headroom's variant).
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
mkdir -p /tmp/variants
python3 - <<'PY'
from safetensors import safe_open
from safetensors.torch import load_file, save_file
src = "passes/src/denoise/neural/lucid-rae-v3.safetensors"
metadata = safe_open(src, "pt").metadata()
for headroom in (-16, -64, -256):
    save_file(load_file(src), f"/tmp/variants/clamp{headroom}.safetensors",
              metadata={**metadata, "firefly_headroom": str(headroom)})
PY
run=/tmp/variants
echo "HELDOUT-START $(date +%s)"
SCENES="caustics" BENCH=0 LUCID=/tmp/bin/lucid \
  ALSO="$run/clamp-16.safetensors $run/clamp-64.safetensors $run/clamp-256.safetensors" \
  training/evaluate_gpu.sh /tmp/eval
echo "HELDOUT-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/out/
/tmp/bin/lucid evaluate /tmp/heldout-caustics --maps > /dev/null
cp /tmp/heldout-caustics/maps/by_brightness.csv /tmp/out/by_brightness_caustics.csv
echo "MAPS-END $(date +%s)"
echo JOB-END
