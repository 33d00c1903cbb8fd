#!/usr/bin/env bash
# Checks formatting and lints, then runs every test (on lavapipe when no GPU driver is present,
# validation layers on).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -- -D warnings
cargo test --workspace "$@"
