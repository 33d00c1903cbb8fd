#!/usr/bin/env bash
# Here (build host), from the project root: what bench/neural_ab_gpu.sh needs on the NVIDIA machine
# to run the learned denoiser's parity test under the Khronos validation layer:
#   bench/pack_parity.sh
# writes .gpu/neural_parity.xz (the parity test's release binary, stripped) and, by
# bench/pack_layers.sh, .gpu/layers.tar.xz (the validation layer).
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
bench/pack_layers.sh
ls -l .gpu/neural_parity.xz
