#!/usr/bin/env bash
# Runs Lucid's main job: a headless render written to lucid.png (arguments are passed to `lucid`).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
if [ "$#" -eq 0 ]; then
  set -- render --scene test-pattern --size 512x512 --out lucid.png
fi
cargo run --release -p lucid-sandbox --bin lucid -- "$@"
