#!/usr/bin/env bash
# Here (build host), from the project root: the Khronos validation layer for the NVIDIA machine,
# whose image has none:
#   bench/pack_layers.sh
# writes .gpu/layers.tar.xz (layers/: this machine's validation layer library and its manifest,
# the library beside it). Unpack it there and point VK_LAYER_PATH at layers/.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p .gpu
manifest=/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json
library=$(ldconfig -p | awk '/libVkLayer_khronos_validation.so/ {print $NF; exit}')
[ -f "$manifest" ] && [ -n "$library" ] || {
  echo "no validation layer here: apt-get install -y vulkan-validationlayers" >&2
  exit 1
}
layers=$(mktemp -d)
mkdir "$layers/layers"
cp "$library" "$layers/layers/"
python3 - "$manifest" "$layers/layers/VkLayer_khronos_validation.json" <<'PY'
import json, sys
manifest = json.load(open(sys.argv[1]))
manifest["layer"]["library_path"] = "./libVkLayer_khronos_validation.so"
json.dump(manifest, open(sys.argv[2], "w"), indent=1)
PY
tar -cJf .gpu/layers.tar.xz -C "$layers" layers
rm -rf "$layers"
ls -l .gpu/layers.tar.xz
