#!/usr/bin/env bash
# Forty-sixth session, run in the forty-seventh (one H200, 542 s; out/ keeps each path's
# growth.json; training/README.md, "The output's history stored exactly, and SVGF's steps rounded").
# runs/v48 found the learned denoiser's error on `caustics` growing on the ordinary lit floor as the
# path goes on (+24% from frames 2-4 to 12-29 in the band of 0.5-2x the mean brightness, twice
# SVGF's growth, six times the per-frame filter's). error_growth.py now also writes, per frame on
# those pixels, the light kept, the relative squared error at the pixel and over 4x4 and 16x16
# blocks (at what scale the error lies: speckle or blotches) and the error's correlation with the
# frame before (how long it persists). On lavapipe at 960x540 (portable inference, 256-sample
# reference) the same path shows no rise at all (0.01666 -> 0.01550), so this also separates the two
# causes that differ: `caustics` at 1080p on the tensor-core path (runs/v48's case), at 1080p on the
# portable path (`--neural-path portable`), and at 960x540; then `classroom` at 1080p, where the
# learned denoiser's error falls along the path. Each with the committed weights and the same with
# the running means capped at 8 frames.
#   source .gpu/env.sh && training/runs/v49-error-scale/job.sh
# About 460 s: 80 s a `caustics` path at 1080p, 25 s at 960x540, some 210 s for `classroom` (its
# 1024-sample reference), 16 s an analysis (runs/v48: 79 s and 16 s).
set -u
mkdir -p /tmp/bin /tmp/pylib
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
python3 -c "import OpenEXR" 2>/dev/null || pip install -q --no-index --no-deps --target /tmp/pylib .gpu/wheels/openexr-*.whl
echo "START $(date +%s)"
(cd training && python3 set_metadata.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors history_frames=8 \
  --out /tmp/w-h8.safetensors)
# NAME SCENE SIZE [sequence options...]
path() {
  local name=$1 scene=$2 size=$3
  shift 3
  rm -rf "/tmp/path-$name"
  /tmp/bin/lucid sequence --scene "$scene" --size "$size" --frames 30 --reference-spp 1024 \
    --out "/tmp/path-$name" --no-evaluate --also-neural-weights /tmp/w-h8.safetensors "$@" > /dev/null
  echo "SEQUENCE-END $name $? $(date +%s)"
  (cd training && PYTHONPATH=/tmp/pylib python3 error_growth.py "/tmp/path-$name" \
    --methods neural neural-w-h8 svgf spatial --early 2 5 --late 12 30 --out "$OUT/growth-$name")
  echo "GROWTH-END $name $? $(date +%s)"
}
path caustics caustics 1920x1080
path caustics-portable caustics 1920x1080 --neural-path portable
path caustics-960 caustics 960x540
path classroom classroom 1920x1080
