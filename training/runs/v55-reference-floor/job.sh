#!/usr/bin/env bash
# Fiftieth session (one H200). Issue #12's targets are measured against one 1024-sample reference,
# whose own noise is in every figure. The fifteenth session estimated from a second reference that
# on `caustics` a third of OIDN's instability, and FLIP near 0.7x SVGF's, lie at or below what a
# noiseless method would measure; that was with the weights, SVGF and noisy frames of then. This
# job measures the floor directly with the current binary (main at HEAD, .gpu/lucid50.xz):
#   1. `caustics` at 1080p, 30 frames against 1024 samples (the issue's path), every method, OIDN
#      per frame where pyoidn imports, a second 1024-sample reference (another seed) as a method;
#   2. the same path's reference at 16384 samples (another seed, so independent of the first),
#      copied in as one more method,
#      `reference-16384`: a near-noiseless image scored against the 1024-sample reference, which
#      is what a perfect denoiser would measure there;
#   3. `classroom` as in 1, its second reference included (a 16384-sample reference would take
#      an hour there).
#   source .gpu/env.sh && WAIT_S=540 training/job_gpu.sh start training/runs/v55-reference-floor/job.sh
#   source .gpu/env.sh && WAIT_S=400 training/job_gpu.sh wait      (the second command)
# Run in 541 + 164 s. `lucid evaluate` then read no `reference-16384/` folder (only the sequence's
# methods, `neural-*`, `oidn` and `second-reference`), so the second command ended with
#   mv /tmp/heldout-caustics/reference-16384 /tmp/heldout-caustics/neural-reference16384
#   /tmp/bin/lucid evaluate /tmp/heldout-caustics --maps
# and out/*_caustics.* are that evaluation's. `lucid sequence --converged-reference-spp 16384`
# (new since) renders and evaluates that image as `converged-reference/` in one command.
set -u
rm -rf /tmp/out /tmp/heldout-* /tmp/c16k && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid50.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
echo "START $(date +%s)"
python3 -c "import pyoidn" && echo "PYOIDN yes" || echo "PYOIDN no"
/tmp/bin/lucid sequence --scene caustics --size 1920x1080 --frames 30 --reference-spp 16384 \
  --seed 7 --out /tmp/c16k --no-evaluate > /tmp/out/c16k.log 2>&1
echo "C16K $? $(date +%s)"
/tmp/bin/lucid sequence --scene caustics --size 1920x1080 --frames 30 --reference-spp 1024 \
  --second-reference --out /tmp/heldout-caustics --no-evaluate > /tmp/out/caustics.log 2>&1
echo "CAUSTICS-RENDER $? $(date +%s)"
python3 -c "import pyoidn" 2>/dev/null && python3 training/oidn_baseline.py /tmp/heldout-caustics >> /tmp/out/caustics.log 2>&1
echo "CAUSTICS-OIDN $? $(date +%s)"
cp -r /tmp/c16k/reference /tmp/heldout-caustics/reference-16384
/tmp/bin/lucid evaluate /tmp/heldout-caustics --maps > /tmp/out/summary_caustics.txt 2>&1
echo "EVAL-CAUSTICS $? $(date +%s)"
cp /tmp/heldout-caustics/metrics.csv /tmp/out/metrics_caustics.csv
cp /tmp/heldout-caustics/maps/by_brightness.csv /tmp/out/by_brightness_caustics.csv
FRAMES=30 BENCH=0 MAPS=1 SECOND_REFERENCE=1 SCENES=classroom LUCID=/tmp/bin/lucid \
  training/evaluate_gpu.sh /tmp/out > /tmp/out/eval_classroom.log 2>&1
echo "EVAL-CLASSROOM $? $(date +%s)"
echo "JOB-END $(date +%s)"
