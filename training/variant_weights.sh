#!/usr/bin/env bash
# The variants a compare_gpu.sh run trained, under short names:
#   training/variant_weights.sh VARIANTS_TAR WEIGHTS_DIR LOG_DIR PATTERN=NAME...
# unpacks VARIANTS_TAR (compare_gpu.sh's variants.tar.gz) and copies each variant's weights to
# WEIGHTS_DIR/w-NAME.safetensors and its log to LOG_DIR/NAME.json, NAME that of the first PATTERN
# (a shell glob over the variant's file name, e.g. '*frames_12*'; '*' for the rest) it matches.
# Prints the names, one a line; a variant no pattern matches is an error.
set -euo pipefail
usage="usage: training/variant_weights.sh VARIANTS_TAR WEIGHTS_DIR LOG_DIR PATTERN=NAME..."
tarball=${1:?$usage}
weights_dir=${2:?$usage}
log_dir=${3:?$usage}
shift 3
[ $# -gt 0 ] || { echo "$usage" >&2; exit 2; }
unpacked=$(mktemp -d)
tar xzf "$tarball" -C "$unpacked"
mkdir -p "$weights_dir" "$log_dir"
for f in "$unpacked"/*.safetensors; do
  name=
  for rule in "$@"; do
    # shellcheck disable=SC2053 # the pattern is a glob on purpose
    if [[ $(basename "$f") == ${rule%=*} ]]; then
      name=${rule##*=}
      break
    fi
  done
  [ -n "$name" ] || { echo "no pattern names $(basename "$f")" >&2; exit 1; }
  cp "$f" "$weights_dir/w-$name.safetensors"
  cp "${f%.safetensors}.json" "$log_dir/$name.json"
  echo "$name"
done
rm -rf "$unpacked"
