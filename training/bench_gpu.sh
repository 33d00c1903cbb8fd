#!/usr/bin/env bash
# Times the learned denoiser on every inference path the device runs, on the NVIDIA machine:
#   training/bench_gpu.sh OUT_DIR
# `lucid bench` on classroom (path tracing, 1 spp, max depth 8, 50 frames after 5 of warm-up) at
# 1920x1080, 1280x720, 854x480 and 640x360, once per path; writes
# OUT_DIR/bench_neural_<path>_<size>.json and OUT_DIR/neural_times.json (per decoder, path and size, the
# median milliseconds of all `neural.*` passes and of each). LUCID names the lucid binary; WEIGHTS,
# a weights file to time instead of the committed one.
set -euo pipefail
out=${1:?usage: training/bench_gpu.sh OUT_DIR}
lucid=$(realpath "${LUCID:-target/release/lucid}")
mkdir -p "$out"
for size in ${SIZES:-1920x1080 1280x720 854x480 640x360}; do
  for path in portable tensor-cores; do
    if ! "$lucid" bench --scene classroom --algo pt --denoise neural --neural-path "$path" \
      --size "$size" --spp 1 --max-depth 8 --frames 50 --warmup 5 \
      ${WEIGHTS:+--neural-weights "$(realpath "$WEIGHTS")"} \
      --json "$out/bench_neural_${path}_$size.json" > /dev/null 2> "$out/bench.err"; then
      echo "bench $path $size: $(tail -1 "$out/bench.err")"
      continue
    fi
    echo "bench $path $size done"
  done
done
rm -f "$out/bench.err"
python3 - "$out" <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])
times = {}
for f in sorted(out.glob("bench_neural_*.json")):
    d = json.loads(f.read_text())
    passes = {k: v["median"] for k, v in d["passes_ms"].items() if k.startswith("neural")}
    key = f"{d['neural_decoder']} {d['neural_path']} {d['size'][0]}x{d['size'][1]}"
    times[key] = {"device": d["device"], "total_ms": round(sum(passes.values()), 3),
                  "passes_ms": {k: round(v, 3) for k, v in passes.items()}}
    print(f"{key}: {times[key]['total_ms']} ms")
(out / "neural_times.json").write_text(json.dumps(times, indent=1))
PY
