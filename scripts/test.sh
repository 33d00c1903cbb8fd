#!/usr/bin/env bash
# Runs every test (on lavapipe when no GPU driver is present, validation layers on).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cargo test --workspace "$@"
