#!/usr/bin/env bash
# Thirty-third session (one H200): the committed weights with their kernels' results averaged in
# linear space rather than in log(1 + x) (experiment.patch: the weights' `linear_domain` metadata,
# 1 = the five kernel scales filter and composite the radiance itself, 2 = the blend with the
# history is linear too), at inference only, untrained, beside the committed weights on the
# held-out paths at 1080p, `caustics` first, then `classroom`; `lucid evaluate --maps` for the
# light each keeps. Writes into OUT as each scene ends: metrics_<scene>.csv, by_brightness_<scene>.csv,
# summary_<scene>.txt.
# .gpu/lucid.xz: the release lucid binary of 6bc7452 with experiment.patch applied.
set -u
out=${1:?usage: job.sh OUT}
mkdir -p /tmp/bin /tmp/variants && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
python3 - <<'PY'
from safetensors import safe_open
from safetensors.torch import load_file, save_file
src = "passes/src/denoise/neural/lucid-rae-v3.safetensors"
metadata = safe_open(src, "pt").metadata()
for domain in (1, 2):
    save_file(load_file(src), f"/tmp/variants/linear{domain}.safetensors",
              metadata={**metadata, "linear_domain": str(domain)})
PY
for scene in caustics classroom; do
  dir=/tmp/linear-$scene
  /tmp/bin/lucid sequence --scene "$scene" --size 1920x1080 --frames 20 --reference-spp 1024 \
    --out "$dir" --no-evaluate --also-neural-weights /tmp/variants/linear1.safetensors \
    --also-neural-weights /tmp/variants/linear2.safetensors > /dev/null
  /tmp/bin/lucid evaluate "$dir" --maps > "$out/summary_$scene.txt"
  cp "$dir/metrics.csv" "$out/metrics_$scene.csv"
  cp "$dir/maps/by_brightness.csv" "$out/by_brightness_$scene.csv"
  echo "DONE $scene $(date +%s)"
done
