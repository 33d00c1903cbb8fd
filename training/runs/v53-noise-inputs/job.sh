#!/usr/bin/env bash
# Forty-ninth session (one H200). On `caustics` the learned denoiser's error stays level over the
# 30 held-out frames while SVGF's falls 13% as the camera slows (runs/v51), and more weight on the
# history does not help (runs/v52). The network sees the running means' deviation and their
# history length n / 32 apart, but not how far the means may still be from the truth, which falls
# as sqrt(n) while the deviation does not. train.py --noise-inputs gives enc0 two more inputs
# (model.noise_inputs: log(1 + the luminance's deviation / sqrt(n)) and the compressed
# luminance's deviation / sqrt(n)), their weights at zero at the start, so the network starts as
# the committed one. runs/v44's recipe side by side from the committed weights (dataset
# SEED_OFFSET 176, the same windows, 4 minutes at lr 1e-3): `control` (the whole network
# fine-tuned) and `noise` (the same with the inputs), each also blended half and half with the
# committed weights (blend.py), and the held-out scenes through PyTorch (study.json: `lucid
# dataset --scenes classroom,caustics`, 3 sequences of 30 frames at 512x512 against 1024 samples).
# First, a check that the model with the inputs at zero weight is the committed network
# (check.json).
#   source .gpu/env.sh && WAIT_S=540 training/job_gpu.sh start training/runs/v53-noise-inputs/job.sh
#   source .gpu/env.sh && training/job_gpu.sh wait      (if the first command ran out first)
# .gpu/lucid49.xz: a release lucid binary (the dataset's renderer; main at ef9dcac): xz -c target/release/lucid.
set -u
rm -rf /tmp/out && mkdir -p /tmp/bin /tmp/out
xz -dc .gpu/lucid49.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
W=fireflies=5e-5+widths=16,32,64,64,32,16+scales=4+crop=256+batch=4+lr=1e-3+cold=0.25+blotch-margin=0.3+blotch=0.2
COMMITTED=passes/src/denoise/neural/lucid-rae-v3.safetensors
echo "START $(date +%s)"
(cd training && python3 - ../$COMMITTED > /tmp/out/check.json) <<'PY' || { echo "CHECK FAILED"; exit 1; }
import json, sys
import torch
from model import RECORD_CHANNELS, split_record
from train import build_model, build_model_for, file_atrous_steps, file_linear_mix, file_recurrent
from train import file_scales, file_widths, load_weights

path = sys.argv[1]
torch.manual_seed(0)
base = build_model_for("kernel", path)
load_weights(base, path)
noisy = build_model("kernel", file_widths(path), file_scales(path), file_linear_mix(path),
                    file_atrous_steps(path), file_recurrent(path), ("noise",))
load_weights(noisy, path)
b, t, h, w = 1, 3, 64, 64
parts = []
for name, n in RECORD_CHANNELS.items():
    x = torch.rand(b, t, n, h, w)
    if name == "demodulated":
        x = x * 4.0
    if name == "normal":
        x = torch.nn.functional.normalize(torch.randn(b, t, 3, h, w), dim=2)
    if name == "depth":
        x = 1.0 + x
    if name == "motion":
        x = torch.cat([torch.zeros(b, t, 2, h, w), torch.zeros(b, t, 1, h, w)], 2)
    parts.append(x)
rec = torch.cat(parts, 2)
# Motion of zero: last frame's depth of the point is this frame's.
channels = list(RECORD_CHANNELS)
depth_at = sum(RECORD_CHANNELS[c] for c in channels[: channels.index("depth")])
rec[:, :, -1] = rec[:, :, depth_at]
with torch.no_grad():
    a, b2 = base(rec), noisy(rec)
    _, state = noisy.step(rec[:, 0], None)
    _, state = noisy.step(rec[:, 1], state)
from model import noise_inputs, variances
with torch.no_grad():
    current = split_record(rec[:, 1])["demodulated"].clamp_min(0.0)
    variance, robust_variance = variances(current, state["accum"], state["moment"], state["robust"])
    extra = noise_inputs(state["accum"], variance, robust_variance)
out = {
    "layers": [list(l) for l in noisy.layers][:1],
    "max_abs_difference": float((a - b2).abs().max()),
    "noise_min": float(extra.min()), "noise_max": float(extra.max()),
    "history_lengths": sorted(set(state["accum"][:, 3].flatten().tolist())),
}
out["max_abs_output"] = float(a.abs().max())
print(json.dumps(out))
assert out["max_abs_difference"] <= 1e-5 * out["max_abs_output"] and torch.isfinite(extra).all() and out["noise_max"] > 0.0, out
PY
cat /tmp/out/check.json
LUCID=/tmp/bin/lucid SHARDS=2 SEED_OFFSET=176 STOPS=0.3 SIZE=512x512 SIZE_FIRST=256x256 ROOMS=6 ROOMS_FIRST=0 \
  FRAMES=32 SEQUENCES=1 VARIANTS="kernel:l1gradflip:0-24:::$W kernel:l1gradflip:0-24:::$W+noise-inputs=" \
  INIT=$COMMITTED MINUTES=${MINUTES:-4} TRAIN_ARGS="--val-every 100000" \
  DATA=/tmp/lucid-dataset training/compare_gpu.sh /tmp/train-out
echo "TRAIN-END $? $(date +%s)"
training/variant_weights.sh /tmp/train-out/variants.tar.gz /tmp /tmp/out '*noise*=noise' '*=control'
for v in control noise; do
  (cd training && python3 blend.py ../$COMMITTED /tmp/w-$v.safetensors --t 0.5 --out /tmp/w-$v-blend.safetensors)
done
cp /tmp/train-out/compare.json /tmp/out/compare.json
tar czf /tmp/out/weights.tgz -C /tmp w-control.safetensors w-noise.safetensors
/tmp/bin/lucid dataset --scenes classroom,caustics --size 512x512 --frames 30 --sequences 3 \
  --reference-spp 1024 --out /tmp/study
(cd training && python3 study_compare.py --data /tmp/study ../$COMMITTED /tmp/w-control.safetensors \
  /tmp/w-noise.safetensors /tmp/w-control-blend.safetensors /tmp/w-noise-blend.safetensors --out /tmp/out/study.json)
echo "STUDY-END $? $(date +%s)"
echo JOB-END
