#!/usr/bin/env bash
# Thirtieth session (one H200): the emission supersampled at emitters' edges (`--edge-emission`)
# with the committed weights, before making it the learned denoiser's default. The held-out
# `classroom` path at 1080p against 1024 samples with the pass (caustics has no emitter edge in view
# and gave the committed figures to the digit in the fifteenth session), then the built-in scenes
# with emitter edges at 960x540 against 512 samples, with and without the pass.
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
echo "HELDOUT-START $(date +%s)"
SCENES=classroom BENCH=0 LUCID=/tmp/bin/lucid OPTIONS=--edge-emission training/evaluate_gpu.sh /tmp/eval
echo "HELDOUT-END $? $(date +%s)"
cp /tmp/eval/metrics_classroom.csv /tmp/out/metrics_classroom_edge_emission.csv
for scene in ${SMALL_SCENES:-cornell-box covered-light blinds-room}; do
  for pass in off on; do
    option=""
    if [ "$pass" = on ]; then option=--edge-emission; fi
    /tmp/bin/lucid sequence --scene "$scene" --size 960x540 --frames 20 --reference-spp 512 \
      --out "/tmp/small-$scene-$pass" --no-evaluate $option
    /tmp/bin/lucid evaluate "/tmp/small-$scene-$pass" > /dev/null
    cp "/tmp/small-$scene-$pass/metrics.csv" "/tmp/out/metrics_${scene}_960x540_edge_emission_$pass.csv"
  done
  echo "SMALL $scene $(date +%s)"
done
tar czf /tmp/out.tgz -C /tmp out
echo JOB-END
