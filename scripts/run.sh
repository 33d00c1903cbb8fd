#!/usr/bin/env bash
# Runs Lucid's main job: a headless render of the Cornell box written to lucid.png (arguments are
# passed to `lucid` instead, e.g. `scripts/run.sh view` opens the sandbox).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
if [ "$#" -eq 0 ]; then
  set -- render --scene cornell-box --size 384x384 --spp 4 --frames 8 --out lucid.png
fi
cargo run --release -p lucid-sandbox --bin lucid -- "$@"
