#!/usr/bin/env bash
# Session 23, job A (4 GPUs): the v13 candidates on the held-out scenes at 1080p (classroom on GPU 0, caustics on GPU 1).
set -u
export GPUS=4
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
echo "EVAL-START $(date +%s)"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid ALSO="training/runs/v13-data/plain.safetensors training/runs/v13-data/blotch_margin.safetensors training/runs/v13-data/blend_t0.1.safetensors" training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $? $(date +%s)"
cp /tmp/eval/metrics_*.csv /tmp/evaluate-*.log /tmp/out/
tar czf /tmp/out.tgz -C /tmp out
echo JOB-END
