#!/usr/bin/env bash
# Session 22, second job (4 GPUs): the dataset again with motion and values saturated (12 shards,
# glossy floors), three 4-minute fine-tunings of the committed blend on GPUs 0-2 (plain; blotch 0.2
# + cold 0.25; blotch 0.2 beyond a 0.3 margin) while GPU 3 A/Bs #15's shaders (base = HEAD, new =
# the path tracer's camera select, BDPT's camera read where used, the motion clamp), then blends
# and the held-out evaluation (classroom on GPU 0, caustics on GPU 1).
set -u
export GPUS=4
mkdir -p /tmp/bin /tmp/out /tmp/b && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
tar -xJf .gpu/bins2.tar.xz -C /tmp/b
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
(
  while ! grep -q "^training " /tmp/job.log; do sleep 5; done
  show() {
    python3 -c "
import json, sys
r = json.load(open('/tmp/r.json'))
regs = ' '.join('%s:%s' % (k.split('/')[-1], v.get('Register Count')) for k, v in r.get('pipelines', {}).items() if 'bdpt' in k or 'path_trace' in k)
print(sys.argv[1], 'image=%.3f' % r['image_ms']['median'], ' '.join('%s=%.3f' % (k, v['median']) for k, v in r['passes_ms'].items() if v['median'] > 0.05), regs)" "$1"
  }
  for round in 1 2; do
    for s in classroom covered-light cornell-box caustics; do
      for b in base new; do
        LUCID_DEVICE='#3' /tmp/b/lucid-$b bench --scene $s --algo pt --size 1920x1080 --spp 1 --max-depth 8 --frames 100 --warmup 10 --pipeline-statistics --json /tmp/r.json > /dev/null 2>&1 && show "$round $s pt $b"
      done
    done
    for s in classroom covered-light cornell-box caustics cornell-teapot blinds-room; do
      for b in base new; do
        LUCID_DEVICE='#3' /tmp/b/lucid-$b bench --scene $s --algo bdpt --size 1920x1080 --spp 1 --max-depth 8 --frames 100 --warmup 10 --pipeline-statistics --json /tmp/r.json > /dev/null 2>&1 && show "$round $s bdpt $b"
      done
    done
    for b in base new; do
      LUCID_DEVICE='#3' /tmp/b/lucid-$b bench --scene classroom --algo pt --denoise svgf --size 1920x1080 --spp 1 --max-depth 8 --frames 100 --warmup 10 --pipeline-statistics --json /tmp/r.json > /dev/null 2>&1 && show "$round classroom pt+svgf $b"
    done
  done
) > /tmp/out/ab.txt 2>&1 &
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4
SHARDS=12 ROOMS=24 FRAMES=32 SEQUENCES=1 LUCID=/tmp/bin/lucid \
  VARIANTS="kernel:l1gradflip:0-12:::$W kernel:l1gradflip:0-12:::$W+blotch=0.2+cold=0.25 kernel:l1gradflip:0-12:::$W+blotch=0.2+blotch-margin=0.3" \
  INIT=passes/src/denoise/neural/lucid-rae-v3.safetensors MINUTES=4 TRAIN_ARGS="--batch 24 --watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $?"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  b=$(basename "$f")
  short=$(echo "$b" | sed -e 's/kernel-l1gradflip-burn0-12-fireflies_5e-5_widths_16_32_64_64_32_16_//')
  cp "$f" "/tmp/w-$short"; cp "${f%.safetensors}.json" "/tmp/out/${short%.safetensors}.json"
done
cp /tmp/train-out/compare.json /tmp/out/
(cd training && for t in 0.1 0.2; do
  python3 blend.py /tmp/w-scales_4.safetensors /tmp/w-scales_4_blotch_0.2_cold_0.25.safetensors --t $t --out /tmp/w-blend_$t.safetensors
done)
also=""
for w in /tmp/w-*.safetensors; do
  if python3 -c "import sys, torch; from safetensors.torch import load_file; sys.exit(0 if all(torch.isfinite(v).all() for v in load_file(sys.argv[1]).values()) else 1)" "$w"; then also="$also $w"; else echo "$w: non-finite, left out"; fi
done
echo "EVAL-START $(date +%s) $also"
SCENES="classroom caustics" BENCH=0 LUCID=/tmp/bin/lucid ALSO="$also" training/evaluate_gpu.sh /tmp/eval
echo "EVAL-END $?"
cp /tmp/eval/metrics_*.csv /tmp/out/
tar czf /tmp/weights.tgz -C /tmp $(cd /tmp && ls w-*.safetensors)
wait
tar czf /tmp/out.tgz -C /tmp out weights.tgz
echo JOB-END
