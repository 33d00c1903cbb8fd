#!/usr/bin/env bash
# The published results (`docs/results/`), in one command, on the NVIDIA machine:
#   docs/results/generate.sh OUT_DIR
# Per scene of SCENES (default: every built-in scene but furnace):
#   - `lucid converge` (still camera): error against GPU time per configuration (ALGOS x
#     DENOISERS x SPP samples per pixel per frame, each for BUDGET_MS of GPU time, at SIZE, against
#     a REFERENCE_SPP reference, measured at the same ladder of GPU times up to BUDGET_MS):
#     OUT_DIR/<scene>/converge.{csv,json} and its charts (error against GPU time, speed against
#     accuracy with the Pareto front, time to converge);
#   - `lucid bench` per algorithm at each of TABLE_SIZES (1 sample, FRAMES frames): the frame
#     time table (the study's Table 4.1): OUT_DIR/<scene>/bench_<algo>_<size>.json.
# Then the denoisers' time on classroom (or the first scene) at each of DENOISER_SIZES (the
# study's Table 4.2): OUT_DIR/denoise_<denoiser>_<size>.json; that scene's camera path through
# every denoiser (`lucid sequence`, STABILITY_SIZE, STABILITY_FRAMES frames, a
# STABILITY_REFERENCE_SPP reference; the frames deleted after the evaluation):
# OUT_DIR/stability/ with metrics.csv, each method's GPU times and the stability chart
# (temporal instability and FLIP against GPU time per frame); and `tables.py` writes
# OUT_DIR/README.md: the tables, DSSIM over accumulated GPU time (the study's Table 4.3), time to
# converge, the charts, device, driver and every command. With MITSUBA the folder of an unpacked
# Mitsuba 3 package (bench/mitsuba/README.md), Lucid against Mitsuba 3 on the Cornell box at
# MITSUBA_SIZE: Mitsuba's images at 16..1024 samples and its reference
# (bench/mitsuba/converge_cornell.py, into MITSUBA_WORK), measured with Lucid's path tracing at 1
# and 16 samples a frame by `lucid converge --reference --external`: OUT_DIR/mitsuba/. LUCID names
# the lucid binary (default target/release/lucid). A small run on lavapipe is part of the tests
# (sandbox/tests/results.rs).
set -euo pipefail
out=${1:?usage: docs/results/generate.sh OUT_DIR}
here=$(cd "$(dirname "$0")" && pwd)
lucid=$(realpath "${LUCID:-target/release/lucid}")
scenes=${SCENES:-cornell-box cornell-teapot covered-light blinds-room classroom caustics}
size=${SIZE:-640x360}
table_sizes=${TABLE_SIZES:-1280x720 1920x1080}
denoiser_sizes=${DENOISER_SIZES:-640x360 854x480 1280x720 1920x1080}
frames=${FRAMES:-50}
mkdir -p "$out"
out=$(realpath "$out")
run() {
  echo "$*" >> "$out/commands.txt"
  "$@"
}
: > "$out/commands.txt"
if command -v nvidia-smi > /dev/null; then
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1 | sed 's/, / (driver /; s/$/)/' > "$out/device.txt"
fi
for scene in $scenes; do
  mkdir -p "$out/$scene"
  run "$lucid" converge --scene "$scene" --size "$size" --algos "${ALGOS:-pt,bdpt}" \
    --denoisers "${DENOISERS:-none,svgf,neural}" --spp "${SPP:-1,4}" --budget-ms "${BUDGET_MS:-1300}" \
    --reference-spp "${REFERENCE_SPP:-4096}" --out "$out/$scene" > "$out/$scene/converge.txt"
  for algo in ${TABLE_ALGOS:-pt bdpt}; do
    for s in $table_sizes; do
      run "$lucid" bench --scene "$scene" --algo "$algo" --size "$s" --spp 1 --frames "$frames" \
        --warmup 3 --json "$out/$scene/bench_${algo}_$s.json" > /dev/null
    done
  done
done
denoise_scene=classroom
case " $scenes " in *" classroom "*) ;; *) denoise_scene=${scenes%% *} ;; esac
for denoiser in ${TABLE_DENOISERS:-svgf neural}; do
  for s in $denoiser_sizes; do
    run "$lucid" bench --scene "$denoise_scene" --algo pt --denoise "$denoiser" --size "$s" --spp 1 \
      --frames "$frames" --warmup 3 --json "$out/denoise_${denoiser}_$s.json" > /dev/null
  done
done
run "$lucid" sequence --scene "$denoise_scene" --size "${STABILITY_SIZE:-1920x1080}" \
  --frames "${STABILITY_FRAMES:-20}" --reference-spp "${STABILITY_REFERENCE_SPP:-1024}" \
  --out "$out/stability" > "$out/stability.txt"
find "$out/stability" -name '*.exr' -delete
if [ -n "${MITSUBA:-}" ]; then
  work=${MITSUBA_WORK:-/tmp/lucid-mitsuba}
  mitsuba_size=${MITSUBA_SIZE:-1920x1080}
  mkdir -p "$out/mitsuba" "$work"
  run env PYTHONPATH="$MITSUBA" python3 "$here/../../bench/mitsuba/converge_cornell.py" \
    --size "$mitsuba_size" --out "$work" > "$out/mitsuba/mitsuba.txt"
  cp "$work/series.json" "$out/mitsuba/series.json"
  run "$lucid" converge --scene cornell-box --size "$mitsuba_size" --algos pt --denoisers none --warmup 30 \
    --spp 1,16 --max-frames 1024 --budget-ms 20000 --reference "$work/reference.exr" \
    --external "Mitsuba 3=$work/series.json" --out "$out/mitsuba" > "$out/mitsuba/converge.txt"
fi
python3 "$here/tables.py" "$out" > "$out/README.md"
echo "-> $out/README.md"
