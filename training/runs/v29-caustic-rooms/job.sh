#!/usr/bin/env bash
# Thirty-fifth session (one H200), after runs/v28-linear-mix-half: there the mix, trained on rooms
# with almost no caustics, settled at one level everywhere. Here the same two variants (the mix
# from one half, `--energy 10`, without fireflies and with `--fireflies 5e-5`) on a fresh dataset
# whose rooms have caustics in about two of five (random_room/caustic.rs; `SEED_OFFSET` 80; the
# validation rooms come from the same generator). Runs in the foreground of one command, writing into
# OUT: compare.json, <variant>.json, weights.tgz. MIX=0: the control, the same two fine-tunings of
# the committed weights without the mix (weights w-no-mix*.safetensors; run in the thirty-sixth
# session: control/, its held-out evaluation by eval.sh in control/eval/).
# .gpu/lucid.xz: the release lucid binary of the commit this file came with.
set -u
out=${1:?usage: job.sh OUT}
mkdir -p /tmp/bin && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
committed=passes/src/denoise/neural/lucid-rae-v3.safetensors
if [ "${MIX:-1}" = 0 ]; then
  name=no-mix
  cp "$committed" /tmp/init.safetensors
else
  name=mix-half
  (cd training && python3 widen_scales.py "../$committed" --linear-mix 0 --out /tmp/init.safetensors)
fi
W=widths=16,32,64,64,32,16+scales=4+crop=368+batch=4+lr=5e-4+cold=0.25+blotch-margin=0.3+blotch=0.2+energy=10
echo "START $(date +%s)"
LUCID=/tmp/bin/lucid SHARDS=4 SEED_OFFSET=80 SIZE=512x512 ROOMS=6 ROOMS_FIRST=0 FRAMES=32 SEQUENCES=1 \
  VARIANTS="kernel:l1gradflip:0-12:::$W kernel:l1gradflip:0-12:::$W+fireflies=5e-5" \
  INIT=/tmp/init.safetensors MINUTES=${MINUTES:-4.5} TRAIN_ARGS="--watch covered-light" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
mkdir -p /tmp/v && tar xzf /tmp/train-out/variants.tar.gz -C /tmp/v
for f in /tmp/v/kernel-*.safetensors; do
  case "$f" in *fireflies*) n=$name-fireflies ;; *) n=$name ;; esac
  cp "$f" "/tmp/w-$n.safetensors"; cp "${f%.safetensors}.json" "$out/$n.json"
done
cp /tmp/train-out/compare.json "$out/"
tar czf "$out/weights.tgz" -C /tmp $(cd /tmp && ls w-*.safetensors)
echo JOB-END
