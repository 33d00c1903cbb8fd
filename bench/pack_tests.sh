#!/usr/bin/env bash
# Here (build host), from the project root: every test of the workspace for the NVIDIA machine,
# where bench/tests_gpu.sh runs them under the validation layer (lavapipe is not a GPU: a result
# that holds on one and not on the other is a bug to find):
#   bench/pack_tests.sh
# builds the release test binaries, strips them and packs them with the release `lucid` binary
# (which the CLI tests run) into .gpu/tests.tar.xz (about 16 MB: the binaries share most of their
# code, which one xz stream with a dictionary larger than each keeps once), with the path of the
# tree they were built in (their fixtures and `lucid` are found there), and writes
# .gpu/layers.tar.xz (bench/pack_layers.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p .gpu
cargo build --release -p lucid-sandbox --bin lucid
pack=$(mktemp -d)
mkdir "$pack/tests"
# Name each binary after its test target, and after its crate's folder too where two crates have
# a target of that name.
cargo test --release --workspace --no-run --message-format=json 2>/dev/null | python3 -c '
import collections, json, sys
found = []
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["profile"]["test"]:
        found.append((m["target"]["name"], m["manifest_path"].split("/")[-2], m["executable"]))
names = collections.Counter(name for name, _, _ in found)
for name, crate, executable in found:
    print(f"{name}-{crate}" if names[name] > 1 else name, executable)
' | while read -r name executable; do
  strip -o "$pack/tests/$name" "$executable"
done
[ -n "$(ls "$pack/tests")" ] || { echo "cargo built no test binaries" >&2; exit 1; }
strip -o "$pack/lucid" target/release/lucid
pwd > "$pack/built_in"
tar -cf - -C "$pack" tests lucid built_in | xz -T2 --lzma2=preset=6,dict=512MiB -c > .gpu/tests.tar.xz
rm -rf "$pack"
bench/pack_layers.sh
ls -l .gpu/tests.tar.xz
