#!/usr/bin/env bash
# Thirty-third session (one H200): how much of the held-out scenes' light each denoiser keeps, by
# the reference's brightness (`lucid evaluate --maps`, its `light` column), at 1920x1080 against the
# 1024-sample reference: `caustics` with SVGF's firefly clamp on (the default) and off, then
# `classroom` with the defaults. Writes OUT/<scene>_<variant>.csv (by_brightness.csv) and .txt (the
# printed summary).
# .gpu/lucid.xz: the release lucid binary with the `light` column (this session).
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
run() {
  local scene=$1 variant=$2
  shift 2
  local dir=/tmp/light-$scene-$variant
  /tmp/bin/lucid sequence --scene "$scene" --size 1920x1080 --frames 20 --reference-spp 1024 \
    --out "$dir" --no-evaluate "$@" > /dev/null
  /tmp/bin/lucid evaluate "$dir" --maps > "/tmp/out/${scene}_$variant.txt"
  cp "$dir/maps/by_brightness.csv" "/tmp/out/${scene}_$variant.csv"
  echo "DONE $scene $variant $(date +%s)"
}
echo "START $(date +%s)"
run caustics defaults
run caustics svgf-clamp-off --svgf-firefly-clamp off
run classroom defaults
echo JOB-END
