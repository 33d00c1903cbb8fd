#!/usr/bin/env bash
# Thirty-fifth session, on this machine after job.sh (its w-*.safetensors untracked beside this
# file): each trained variant blended at t = 0.5 with its start (the committed weights widened with
# the mix at one half), the twenty-eighth session's recipe; once plainly (w-blend-<v>-0.5) and once
# with the mix's channel taken whole from the trained variant (w-blend-<v>-own-mix).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
cd "$here/../.."
python3 widen_scales.py ../passes/src/denoise/neural/lucid-rae-v3.safetensors --linear-mix 0 --out /tmp/init-mix.safetensors
for v in mix-half mix-half-fireflies; do
  python3 blend.py /tmp/init-mix.safetensors "$here/w-$v.safetensors" --t 0.5 --out "$here/w-blend-$v-0.5.safetensors"
  python3 blend.py /tmp/init-mix.safetensors "$here/w-$v.safetensors" --t 0.5 --mix-from-b \
    --out "$here/w-blend-$v-own-mix.safetensors"
done
