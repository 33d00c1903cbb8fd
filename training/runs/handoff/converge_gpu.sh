#!/usr/bin/env bash
# Twenty-seventh session: the still-camera hand-off (passes/src/denoise/handoff) against the learned
# denoiser alone and plain accumulation, every built-in scene but the furnace, 640x360, path
# tracing at 1 sample a frame, up to 1024 frames, on the NVIDIA machine:
#   source .gpu/env.sh && training/runs/handoff/converge_gpu.sh OUT_DIR
# .gpu/main.xz: the binary before the hand-off (the learned denoiser alone); .gpu/new.xz: with it.
# Twenty-eighth session: DENOISER=svgf measures SVGF's temporal mode the same way (its hand-off
# came in the twenty-eighth session); SCENES, the scenes; BINS, the binaries of .gpu (main and new,
# others as main: no plain accumulation).
set -eu
out=${1:?usage: converge_gpu.sh OUT_DIR}
mkdir -p /tmp/bin "$out"
for b in ${BINS:-main new}; do xz -dc ".gpu/$b.xz" > "/tmp/bin/$b" && chmod +x "/tmp/bin/$b"; done
for scene in ${SCENES:-cornell-box cornell-teapot blinds-room classroom covered-light caustics}; do
  for b in ${BINS:-main new}; do
    denoisers=${DENOISER:-neural}
    if [ "$b" = new ]; then denoisers=$denoisers,none; fi
    "/tmp/bin/$b" converge --scene "$scene" --size 640x360 --algos pt --denoisers "$denoisers" --spp 1 \
      --max-frames 1024 --budget-ms 4000 --out "/tmp/conv-$scene-$b" > "/tmp/conv-$scene-$b.log" 2>&1
    cp "/tmp/conv-$scene-$b/converge.csv" "$out/$scene-$b${DENOISER:+-$DENOISER}.csv"
    tail -4 "/tmp/conv-$scene-$b.log"
  done
done
