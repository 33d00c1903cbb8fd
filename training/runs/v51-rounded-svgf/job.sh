#!/usr/bin/env bash
# Forty-seventh session, for the next session's device time (one H200; not yet run). SVGF's a-trous
# steps (and the per-frame spatial filter, the same steps) now round their rgba16f stores to
# nearest (`round_to_half`), where the stores' own conversion truncated on every device: on lavapipe
# at 320x180 SVGF's FLIP on `caustics` fell 8%. runs/v50's ratios of the learned denoiser to SVGF
# (0.756x and 0.692x FLIP) are against SVGF before that. This job runs, with the release binary of
# the commit it came with (.gpu/lucid.xz) and its test binaries (.gpu/half_rounding.xz,
# .gpu/neural_parity.xz, .gpu/svgf_constant.xz; bench/pack_parity.sh's .gpu/layers.tar.xz):
#   1. tests/tests/half_rounding.rs and svgf_constant.rs (not yet run on NVIDIA: `round_to_half`
#      through an rgba16f store, and SVGF keeping a constant with it) and neural_parity.rs;
#   2. the held-out paths at 1080p, 30 frames against 1024 samples (as runs/v50), also with two
#      weights judged before only against the truncated history: the running means capped at 8
#      frames (runs/v48) and runs/v44's `control` fine-tuning blended half and half (runs/v45);
#   3. SVGF's time on `classroom` at 1080p, the binary before the rounding (.gpu/lucid_before.xz,
#      runs/v50's) and after, two rounds back to back.
#   source .gpu/env.sh && training/job_gpu.sh start training/runs/v51-rounded-svgf/job.sh
# About 480 s (runs/v50: 507 s with two parity binaries and four denoiser benches).
set -u
rm -rf /tmp/out /tmp/heldout-* && mkdir -p /tmp/bin /tmp/out /tmp/b
xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
xz -dc .gpu/lucid_before.xz > /tmp/bin/lucid_before && chmod +x /tmp/bin/lucid_before
for x in half_rounding neural_parity svgf_constant; do xz -dc ".gpu/$x.xz" > "/tmp/b/$x" && chmod +x "/tmp/b/$x"; done
tar -xJf .gpu/layers.tar.xz -C /tmp/b
# The tests read their fixtures from the tree they were built in.
[ -e /work/main ] || { mkdir -p /work; ln -s "$PWD" /work/main; }
COMMITTED=passes/src/denoise/neural/lucid-rae-v3.safetensors
(cd training && python3 set_metadata.py ../$COMMITTED history_frames=8 --out /tmp/w-h8.safetensors &&
  python3 blend.py ../$COMMITTED runs/v44-motion-inputs/out/w-control.safetensors --t 0.5 \
    --out /tmp/w-control-blend-5.safetensors)
echo "START $(date +%s)"
for x in half_rounding neural_parity svgf_constant; do
  VK_LAYER_PATH=/tmp/b/layers LUCID_VALIDATION=1 "/tmp/b/$x" --test-threads 1 > "/tmp/out/test_$x.log" 2>&1
  echo "TEST $x $?"
done
FRAMES=30 FIRST=16 BENCH=0 MAPS=1 OIDN=0 SCENES="caustics classroom" LUCID=/tmp/bin/lucid \
  ALSO="/tmp/w-h8.safetensors /tmp/w-control-blend-5.safetensors" training/evaluate_gpu.sh /tmp/out
echo "EVAL-END $? $(date +%s)"
for round in 1 2; do
  for b in lucid_before lucid; do
    "/tmp/bin/$b" bench --scene classroom --algo pt --denoise svgf --size 1920x1080 --spp 1 \
      --max-depth 8 --frames 50 --warmup 5 --json "/tmp/out/bench_svgf_${b}_$round.json" > /dev/null
  done
done
echo "JOB-END $(date +%s)"
