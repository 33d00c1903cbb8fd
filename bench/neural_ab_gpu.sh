#!/usr/bin/env bash
# On the NVIDIA machine: the learned denoiser's parity test under the Khronos validation layer,
# then an A/B of lucid binaries' denoiser time, back to back:
#   bench/neural_ab_gpu.sh OUT_DIR BIN[:WEIGHTS]...
# Each BIN is an xz-compressed lucid binary in .gpu/ (`.gpu/BIN.xz`), run with the committed
# weights or, given WEIGHTS, with that weights file (`--neural-weights`; its file name then tags
# the runs: BIN-<stem>); `.gpu/neural_parity.xz` is
# the parity test's binary (`cargo test --release -p lucid-tests --test neural_parity --no-run`,
# stripped) and `.gpu/layers.tar.xz` holds `layers/` with the validation layer's library and its
# manifest (library_path "./libVkLayer_khronos_validation.so"); bench/pack_parity.sh writes both
# here. For ROUNDS rounds (2) and each
# size of SIZES (1920x1080 854x480), every binary runs `lucid bench --scene classroom --algo pt
# --denoise neural --neural-path PATH (tensor-cores) --spp 1 --max-depth 8 --frames 50 --warmup 5`;
# writes OUT_DIR/ab.json (per binary, size and round, the median of each `neural.*` pass and their
# sum) and prints the sums.
set -euo pipefail
out=$(realpath "${1:?usage: bench/neural_ab_gpu.sh OUT_DIR BIN...}")
shift
bin=/tmp/neural-ab
mkdir -p "$out" "$bin"
for spec in "$@" neural_parity; do
  b=${spec%%:*}
  xz -dc ".gpu/$b.xz" > "$bin/$b"
  chmod +x "$bin/$b"
done
tar -xJf .gpu/layers.tar.xz -C "$bin"
export VK_LAYER_PATH="$bin/layers"
# The test reads its fixtures from the tree it was built in.
built_in=/work/main
[ -e "$built_in" ] || { mkdir -p "$(dirname "$built_in")"; ln -s "$PWD" "$built_in"; }
LUCID_VALIDATION=1 "$bin/neural_parity" --test-threads 1 2>&1 | tee "$out/parity.log" | tail -n 8
for round in $(seq "${ROUNDS:-2}"); do
  for size in ${SIZES:-1920x1080 854x480}; do
    for spec in "$@"; do
      b=${spec%%:*}
      weights=()
      tag=$b
      if [ "$spec" != "$b" ]; then
        weights=(--neural-weights "$(realpath "${spec#*:}")")
        tag=$b-$(basename "${spec#*:}" .safetensors)
      fi
      "$bin/$b" bench --scene classroom --algo pt --denoise neural --neural-path "${NEURAL_PATH:-tensor-cores}" \
        --size "$size" --spp 1 --max-depth 8 --frames 50 --warmup 5 "${weights[@]}" \
        --json "$out/bench_${tag}_${size}_$round.json" > /dev/null
    done
  done
done
python3 - "$out" <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])
rows = {}
for f in sorted(out.glob("bench_*.json")):
    d = json.loads(f.read_text())
    passes = {k: v["median"] for k, v in d["passes_ms"].items() if k.startswith("neural")}
    rows[f.stem] = {"device": d["device"], "total_ms": round(sum(passes.values()), 3),
                    "passes_ms": {k: round(v, 3) for k, v in sorted(passes.items())}}
    print(f"{f.stem}: {rows[f.stem]['total_ms']} ms  " +
          " ".join(f"{k.removeprefix('neural.')}={v:.3f}" for k, v in sorted(passes.items()) if v >= 0.05))
(out / "ab.json").write_text(json.dumps(rows, indent=1))
PY
