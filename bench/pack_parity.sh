#!/usr/bin/env bash
# Here (build host), from the project root: what bench/neural_ab_gpu.sh needs on the NVIDIA machine
# to run the learned denoiser's parity test under the Khronos validation layer:
#   bench/pack_parity.sh
# writes .gpu/neural_parity.xz (the parity test's release binary, stripped) and .gpu/layers.tar.xz
# (layers/: this machine's validation layer library and its manifest, the library beside it).
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p .gpu
test_binary=$(cargo test --release -p lucid-tests --test neural_parity --no-run --message-format=json 2>/dev/null |
  python3 -c 'import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["name"] == "neural_parity":
        print(m["executable"])')
[ -n "$test_binary" ] || { echo "cargo built no neural_parity test binary" >&2; exit 1; }
strip -o /tmp/neural_parity "$test_binary"
xz -T2 -6 -c /tmp/neural_parity > .gpu/neural_parity.xz
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
ls -l .gpu/neural_parity.xz .gpu/layers.tar.xz
