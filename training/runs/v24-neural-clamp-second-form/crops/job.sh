#!/usr/bin/env bash
# Thirty-third session (one H200): where the learned denoiser's relMSE spikes on the held-out
# `caustics` path come from. Renders its first 12 frames at 1080p (every method, 1024-sample
# reference; the same frames as the evaluations), then per frame the worst 32x32 block of relative
# squared error of `neural` and `svgf` (blocks.txt), and 96x96 crops around `neural`'s worst block
# of the reference, both denoisers, the noisy input and the albedo (crops.npz; crops.png shows frames
# 5-10, a row a frame, in that order, tone-mapped 1 - exp(-2x)). Reads EXR with exr_read.py (the
# machine's Python has no EXR module). .gpu/lucid.xz: the release lucid binary of 52b0d2c.
set -u
here=$(dirname "$(realpath "$0")")
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
[ -d /tmp/d/reference ] || /tmp/bin/lucid sequence --scene caustics --size 1920x1080 --frames 12 --reference-spp 1024 --out /tmp/d --no-evaluate
HERE="$here" python3 - <<'PY'
import os, sys
sys.path.insert(0, os.environ["HERE"])
import numpy as np
from exr_read import read_exr as load
out = {}
lines = []
for fr in range(12):
    ref = load(f'/tmp/d/reference/{fr:04d}.exr')
    for m in ('neural', 'svgf'):
        x = load(f'/tmp/d/{m}/{fr:04d}.exr')
        rse = ((x - ref) ** 2 / (ref ** 2 + 0.01)).mean(-1)
        h, w = rse.shape
        b = rse[: h // 32 * 32, : w // 32 * 32].reshape(h // 32, 32, w // 32, 32).sum((1, 3))
        iy, ix = np.unravel_index(np.argmax(b), b.shape)
        lines.append(f'{fr} {m} mean {rse.mean():.5f} worst32 {b.max()/rse.size:.5f} at {iy*32},{ix*32} maxpix {rse.max():.1f}')
        if m == 'neural':
            out[f'block_{fr}'] = np.array([iy * 32, ix * 32])
open('/tmp/out/blocks.txt', 'w').write('\n'.join(lines))
# crops 96x96 around each frame's worst neural block, every method, frames 4-11
for fr in range(12):
    y, x = out[f'block_{fr}']
    y0, x0 = max(0, min(1080 - 96, y - 32)), max(0, min(1920 - 96, x - 32))
    for m in ('reference', 'neural', 'svgf', 'none', 'albedo'):
        out[f'{m}_{fr}'] = load(f'/tmp/d/{m}/{fr:04d}.exr')[y0:y0+96, x0:x0+96].astype(np.float16)
    out[f'origin_{fr}'] = np.array([y0, x0])
np.savez_compressed('/tmp/out/crops.npz', **out)
PY
echo JOB-END
