#!/usr/bin/env bash
# Thirty-fourth session: the two weights of job.sh (w-*.safetensors, untracked beside this file)
# held out at 1080p beside the committed weights, `caustics` then `classroom`, with `lucid
# evaluate --maps`; writes metrics_<scene>.csv, by_brightness_<scene>.csv, summary_<scene>.txt
# into OUT as each scene ends.
set -u
out=${1:?usage: eval.sh OUT}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p /tmp/bin && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
for scene in caustics classroom; do
  dir=/tmp/heldout-$scene
  /tmp/bin/lucid sequence --scene "$scene" --size 1920x1080 --frames 20 --reference-spp 1024 \
    --out "$dir" --no-evaluate $(for w in "$here"/w-*.safetensors; do echo "--also-neural-weights $w"; done) > /dev/null
  /tmp/bin/lucid evaluate "$dir" --maps > "$out/summary_$scene.txt"
  cp "$dir/metrics.csv" "$out/metrics_$scene.csv"
  cp "$dir/maps/by_brightness.csv" "$out/by_brightness_$scene.csv"
  echo "DONE $scene $(date +%s)"
done
