"""Trains the recurrent denoiser on `lucid dataset` output and exports its weights.

    python3 train.py --data DIR --minutes 6 --out weights.safetensors --log train.json [--init W]
        [--model direct|kernel] [--loss l1grad|l1msssim|l1gradflip] [--burn-in K [--burn-in-min J]]
        [--widths E0,E1,E2,B,D1,D0] [--scales N] [--fireflies RATE] [--watch SCENES]
        [--blotch WEIGHT [--blotch-margin M]] [--cold P] [--linear-mix] [--energy WEIGHT]
        [--atrous-steps S1,S2,...] [--gate-only | --train-layers NAMES]

`--model kernel` trains `kernel_model.KernelDenoiser` (both export as `lucid-rae-v3`, the decoder
named in the file's `decoder` metadata; the renderer runs either); `--loss` picks a loss of `losses.py`; `--burn-in K` runs the first K
frames of each window without gradients and without loss, so that the recurrent state has warmed
up when the loss starts; with `--burn-in-min J`, each step draws its burn-in from J to K, so that
the loss also sees the first frames after a cut (the renderer's first frames have no history);
`--widths` sets the U-Net's channel counts (a wider `--init` is narrowed to them); `--fireflies`
adds isolated bright samples to the training inputs (not the references), so that the network
learns to drop what no neighbour or frame supports; `--blotch W` adds W times the windows' mean
worst 8x8 block excess (`losses.worst_block_excess`, what the lavapipe blotch test bounds) to the
loss, with `--blotch-margin M` only what exceeds M, so that blocks a little bright cost nothing and
only blotches are pushed down; `--cold P` starts a window at the cut (no burn-in, its first frame
without history) with probability P before the burn-in is drawn, and then weighs its frames alike
rather than the later ones more, so that the first frames after a cut count as much as the settled
ones. `--linear-mix` gives the kernel decoder its per-pixel mix of log-space and linear-space
filtering (`kernel_model.py`; weights without it start it at sigmoid(LINEAR_MIX_BIAS); an `--init`
that has it implies it); `--energy W`
adds W times `losses.energy_l1` (the light of 8x8 blocks against the reference's, what a denoiser
that erases a caustic loses) to the loss. `--atrous-steps 4,8,16` gives either decoder the gated
a-trous filter over its output (`model.atrous`, steps of those spacings in pixels, the gate one
more channel of `out`, its last; written to the weights' `atrous_steps` metadata): weights without
the gate start it at sigmoid(ATROUS_GATE_BIAS) everywhere, an `--init` that has it implies its
steps (other steps are an error). `--gate-only` trains the gate alone (the last output channel of
`out`; everything else stays --init's): the output, the state and so every frame's unfiltered
result stay the initial weights', and only where the filter is blended in is learned. `--train-layers
out,out_half` trains only the layers named (their names in the weights file), every other weight
kept as --init's. A step whose loss is not finite is skipped (and counted); past
1% of the steps, training stops.

Started by `python3 parallel.py N train.py ...` it trains data-parallel on N GPUs (`parallel.py`): each
process loads its share of the sequences, the gradients are averaged, the batch is N times
`--batch`, and the first process validates and writes the weights and the log.
"""

import argparse
import contextlib
import json
import math
import time

import torch
import torch.nn as nn
from safetensors import safe_open
from safetensors.torch import load_file, save_file

from data import add_fireflies, load_split, sample_batch
from kernel_model import (
    HEAD_NAMES,
    LINEAR_MIX_BIAS,
    SCALES,
    TAPS,
    KernelDenoiser,
    kernel_layers,
    linear_mix_of,
    scales_of,
)
from kernel_model import export_tensors as kernel_export_tensors
from losses import (
    DEFAULT_WEIGHTS,
    LOSSES,
    TERM_NAMES,
    display_ssim,
    energy_l1,
    flip,
    light_kept,
    log_tonemap,
    loss_fn,
    relmse,
    temporal_l1,
    worst_block_excess,
)
from model import (
    ATROUS_GATE_BIAS,
    DECODERS,
    FORMAT,
    HIDDEN,
    EXTRA_INPUTS,
    N_MAX,
    RECORD_SIZE,
    WIDTHS,
    RecurrentDenoiser,
    atrous_steps_of,
    export_tensors,
    extras_of,
    sources,
    widths_of,
)
from parallel import Group

MODELS = DECODERS
# The bias of a new coarser scale's weight `a` in the head that composites it, when weights of
# fewer scales start a model of more (load_weights): sigmoid(-3), almost unused.
NEW_SCALE_BIAS = -3.0
# How far apart the data-parallel processes' seeds are: each draws its own windows.
PROCESS_SEED_STRIDE = 7919


def build_model(name, widths=WIDTHS, scales=SCALES, linear_mix=False, atrous_steps=(), recurrent=0, extras=()):
    """The `name`d decoder's model of `widths` (`scales` and `linear_mix` for the kernel decoder),
    with the gated a-trous filter of `atrous_steps` when there are any, `recurrent` channels of
    recurrent state and the extra inputs `extras` (`model.EXTRA_INPUTS`)."""
    if name == "kernel":
        return KernelDenoiser(widths, scales, linear_mix, atrous_steps, recurrent, extras)
    return RecurrentDenoiser(widths, atrous_steps, recurrent, extras)


def build_model_for(decoder, path):
    """The `decoder`'s model shaped as the weights file `path` is: its widths, kernel scales,
    linear mix, a-trous filter's steps, recurrent state and extra inputs (its weights not loaded:
    `load_weights`)."""
    return build_model(
        decoder,
        file_widths(path),
        file_scales(path),
        file_linear_mix(path),
        file_atrous_steps(path),
        file_recurrent(path),
        file_extras(path),
    )


def file_widths(path):
    """The U-Net widths of a weights file train.py wrote."""
    with safe_open(path, "pt") as f:
        return tuple(int(f.get_slice(f"{name}.weight").get_shape()[0]) for name in HIDDEN)


def file_scales(path):
    """The kernel decoder's scales in a weights file train.py wrote."""
    with safe_open(path, "pt") as f:
        return scales_of(set(f.keys()))


def file_atrous_steps(path):
    """The a-trous filter's steps in a weights file train.py wrote (its `atrous_steps` metadata; ()
    where it has none: no gate)."""
    with safe_open(path, "pt") as f:
        return atrous_steps_of((f.metadata() or {}).get("atrous_steps", ""))


def file_recurrent(path):
    """The channels of recurrent state of a weights file train.py wrote (its layer `recurrent`'s
    outputs; 0 where it has none)."""
    with safe_open(path, "pt") as f:
        return int(f.get_slice("recurrent.weight").get_shape()[0]) if "recurrent.weight" in f.keys() else 0


def file_extras(path):
    """The extra inputs (`model.EXTRA_INPUTS`) a weights file train.py wrote reads: those its
    `<name>_inputs` metadata names with their channels."""
    with safe_open(path, "pt") as f:
        meta = f.metadata() or {}
    return tuple(name for name, n in EXTRA_INPUTS.items() if meta.get(f"{name}_inputs", "") == str(n))


def file_linear_mix(path):
    """Whether a kernel-decoder weights file train.py wrote has the linear mix."""
    gate = bool(file_atrous_steps(path))
    with safe_open(path, "pt") as f:
        scales = scales_of(set(f.keys()))
        return scales >= 3 and linear_mix_of(int(f.get_slice("out.weight").get_shape()[0]), scales, gate)


def named_convs(model):
    """The model's convolutions under the names its weights file uses."""
    if isinstance(model, KernelDenoiser):
        return model.named_convs()
    return {name: model.convs[name] for name, _, _ in model.layers}


def narrow(tensors, widths):
    """A wider network's `tensors` cut down to `widths`: a narrowed layer keeps the output channels
    the layers reading them weigh most (the L2 norm of those weights), and those layers keep the
    matching input channels."""
    have = dict(zip(HIDDEN, widths_of(tensors)))
    want = dict(zip(HIDDEN, widths))
    wider = [name for name in HIDDEN if want[name] > have[name]]
    if wider:
        raise ValueError(f"layers {wider} are wider than the file's ({have})")
    layers = [name.removesuffix(".weight") for name in tensors if name.endswith(".weight")]

    def offset(layer, source):
        read = sources(layer)
        return sum(have[s] for s in read[: read.index(source)] if s is not None)

    kept = {}
    for name in HIDDEN:
        norms = torch.zeros(have[name])
        for layer in layers:
            if name in sources(layer):
                at = offset(layer, name)
                norms += tensors[f"{layer}.weight"][:, at : at + have[name]].float().pow(2).sum((0, 2, 3))
        kept[name] = torch.topk(norms, want[name]).indices.sort().values
    out = {}
    for layer in layers:
        w, b = tensors[f"{layer}.weight"], tensors[f"{layer}.bias"]
        if layer in kept:
            w, b = w[kept[layer]], b[kept[layer]]
        columns = [
            torch.arange(w.shape[1]) if s is None else offset(layer, s) + kept[s] for s in sources(layer)
        ]
        out[f"{layer}.weight"] = w[:, torch.cat(columns)].contiguous()
        out[f"{layer}.bias"] = b.contiguous()
    return out


def grown_out(w, b, had, has):
    """The `out` layer's weight and bias `w`, `b` of a file with the optional channels `had` (the
    linear mix's, the gate's: two bools) laid out for a model with `has`: each channel the file
    lacks and the model has starts with weights 0 and its bias (LINEAR_MIX_BIAS, ATROUS_GATE_BIAS),
    so that it starts near the file's output. A file with a channel the model lacks is left as it
    is (its shape is not the model's)."""
    if had == has or any(h and not m for h, m in zip(had, has)):
        return w, b
    base = w.shape[0] - sum(had)
    weights, biases, at = [w[:base]], [b[:base]], base
    for h, m, bias in zip(had, has, (LINEAR_MIX_BIAS, ATROUS_GATE_BIAS)):
        if h:
            weights.append(w[at : at + 1])
            biases.append(b[at : at + 1])
            at += 1
        elif m:
            weights.append(w.new_zeros(1, *w.shape[1:]))
            biases.append(b.new_full((1,), bias))
    return torch.cat(weights), torch.cat(biases)


def load_weights(model, path):
    """Copies the tensors of a file train.py wrote into `model`. The direct model needs all of its
    layers; the kernel model takes every layer whose shapes match (so direct weights start its
    shared layers) and starts the others afresh. A `lucid-rae-v2` file's first layer, which has
    fewer inputs, starts the first layer with the new inputs' weights at zero. The file's
    `emission_motion`, `history_frames`, `spatial_variance_frames` and `atrous_steps` metadata,
    when there, set the model's (a file with `atrous_steps` needs a model with the gate). A file of a
    wider network starts a narrower model from the channels its layers weigh most (`narrow`). A
    file of fewer kernel scales starts a model of more: its coarsest head gains the weight `a` of
    the new scale, at sigmoid(NEW_SCALE_BIAS) everywhere, so that the new scale starts almost
    unused. A file without the linear mix or the gate starts a model with them at
    sigmoid(LINEAR_MIX_BIAS) and sigmoid(ATROUS_GATE_BIAS) everywhere (`grown_out`). A file
    without recurrent state starts a model with it as the v2 file's first layer above: `enc0`'s
    weights for the state at zero, the layer `recurrent` afresh."""
    tensors = load_file(path)
    widths = widths_of(tensors) if all(f"{name}.weight" in tensors for name in HIDDEN) else model.widths
    if widths != model.widths:
        print(f"--init: {path}'s widths {widths} narrowed to {model.widths}", flush=True)
        tensors = narrow(tensors, model.widths)
    with safe_open(path, "pt") as f:
        meta = f.metadata() or {}
    if "emission_motion" in meta:
        model.emission_motion = float(meta["emission_motion"])
    if "history_frames" in meta:
        model.history_frames = int(meta["history_frames"])
    if "spatial_variance_frames" in meta:
        model.spatial_variance_frames = int(meta["spatial_variance_frames"])
    steps = atrous_steps_of(meta.get("atrous_steps", ""))
    if steps:
        if not model.gate:
            raise ValueError(
                f"{path} has the a-trous filter's gate (atrous_steps {meta['atrous_steps']}): the model needs it"
            )
        model.atrous_steps = steps
    recurrent = file_recurrent(path)
    if recurrent and recurrent != model.recurrent:
        raise ValueError(f"{path} has {recurrent} channels of recurrent state: the model has {model.recurrent}")
    extras = file_extras(path)
    # `enc0`'s columns of inputs the file lacks are appended at zero: they must follow its own.
    if model.extras[: len(extras)] != extras:
        raise ValueError(f"{path} reads the extra inputs {list(extras)}: the model reads {list(model.extras)}")
    if recurrent and model.extras != extras:
        raise ValueError(f"{path} has recurrent state where the model reads more extra inputs: start from a file without")
    had = (file_linear_mix(path), bool(steps))
    has = (getattr(model, "linear_mix", False), model.gate)
    loaded, skipped = [], []
    with torch.no_grad():
        for name, conv in named_convs(model).items():
            w, b = tensors.get(f"{name}.weight"), tensors.get(f"{name}.bias")
            if name == "enc0" and w is not None and w.shape[1] < conv.weight.shape[1]:
                w = torch.cat([w, w.new_zeros(w.shape[0], conv.weight.shape[1] - w.shape[1], 3, 3)], 1)
            if name in HEAD_NAMES and w is not None and w.shape[0] == TAPS == conv.weight.shape[0] - 1:
                w = torch.cat([w, w.new_zeros(1, *w.shape[1:])])
                b = torch.cat([b, b.new_full((1,), NEW_SCALE_BIAS)])
            elif name == "out" and w is not None and b is not None:
                w, b = grown_out(w, b, had, has)
            if w is None or b is None or w.shape != conv.weight.shape or b.shape != conv.bias.shape:
                skipped.append(name)
                continue
            conv.weight.copy_(w)
            conv.bias.copy_(b)
            loaded.append(name)
    if isinstance(model, KernelDenoiser) and loaded:
        print(f"--init: loaded {loaded}, started afresh {skipped}", flush=True)
    elif skipped:
        raise ValueError(f"{path}: no tensors or other shapes for layers {skipped}")


def model_cost(model, device, size=64):
    """Parameters and multiply-adds per pixel of one frame (convolutions counted by running one
    step on a size x size frame, plus what the model declares besides: the kernel model's
    filtering)."""
    macs = 0

    def count(mod, _inputs, out):
        nonlocal macs
        macs += out[0].numel() * (mod.in_channels // mod.groups) * mod.kernel_size[0] * mod.kernel_size[1]

    handles = [m.register_forward_hook(count) for m in model.modules() if isinstance(m, nn.Conv2d)]
    try:
        with torch.no_grad():
            model.step(torch.zeros(1, RECORD_SIZE, size, size, device=device), None)
    finally:
        for h in handles:
            h.remove()
    per_pixel = macs / (size * size) + getattr(model, "EXTRA_MACS_PER_PIXEL", 0.0)
    return {
        "parameters": sum(p.numel() for p in model.parameters()),
        "macs_per_pixel": round(per_pixel, 1),
        "flops_per_pixel": round(2 * per_pixel, 1),
    }


@torch.no_grad()
def validate(model, sequences):
    """Over whole sequences, from no history: mean relMSE, mean SSIM and FLIP (per frame, as
    `lucid evaluate` computes them: SSIM on the luminance of the ACES + sRGB display images, FLIP
    on the ACES-mapped ones), temporal instability (mean |frame difference| of output minus
    reference's, in log space), blotches (the worst 8x8 block's excess brightness per frame, as
    the lavapipe blotch test measures it, `losses.worst_block_excess`) and the share of the light
    kept in the brightest pixels (`losses.light_kept`, over the sequences that have such pixels; 1
    where none has)."""
    model.eval()
    keys = ("relmse", "ssim", "flip", "temporal", "blotch")
    sums = dict.fromkeys(keys, 0.0)
    kept = []
    for s in sequences:
        rec = s["record"].float().unsqueeze(0)
        ref = s["reference"].float().unsqueeze(0)
        out = model(rec, objects=s["objects"].unsqueeze(0))
        sums["relmse"] += relmse(out, ref).item()
        sums["ssim"] += display_ssim(out[0], ref[0]).mean().item()
        sums["flip"] += flip(out[0], ref[0]).mean().item()
        sums["temporal"] += temporal_l1(log_tonemap(out), log_tonemap(ref)).item()
        sums["blotch"] += worst_block_excess(out[0], ref[0]).mean().item()
        share = light_kept(out[0], ref[0])
        if share is not None:
            kept.append(share)
    model.train()
    means = {k: v / len(sequences) for k, v in sums.items()}
    means["light"] = sum(kept) / len(kept) if kept else 1.0
    return means


def watched(root, scenes, device):
    """The training sequences of `scenes` (comma-separated names; empty: none), validated on their
    own beside the validation sequences (`--watch`)."""
    names = [n for n in scenes.split(",") if n]
    if not names:
        return []
    found = load_split(root, "train", device, scenes=set(names))
    missing = sorted(set(names) - {s["scene"] for s in found})
    if missing:
        raise SystemExit(f"--watch: no training sequences of {', '.join(missing)}")
    return found


def validation(model, val, watch):
    """`validate` over the validation sequences, and over the watched ones under `watch`."""
    result = validate(model, val)
    if watch:
        result["watch"] = validate(model, watch)
    return result


def train_gate_only(model):
    """Freezes every weight of `model` but its gate's: the last output channel of `out` (its
    weights' other rows get no gradient, so Adam leaves them as they are)."""
    for p in model.parameters():
        p.requires_grad_(False)
    out = named_convs(model)["out"]
    for p in (out.weight, out.bias):
        p.requires_grad_(True)
        last = torch.zeros_like(p)
        last[-1] = 1.0
        p.register_hook(lambda grad, last=last: grad * last)


def train_state_only(model):
    """Freezes every weight of `model` but its recurrent state's: the layer `recurrent` and the
    columns of `enc0`'s weights that read the state (its last `model.recurrent` inputs), so that
    the rest of the network stays --init's and the state can only add to it."""
    for p in model.parameters():
        p.requires_grad_(False)
    convs = named_convs(model)
    for p in convs["recurrent"].parameters():
        p.requires_grad_(True)
    weight = convs["enc0"].weight
    weight.requires_grad_(True)
    columns = torch.zeros_like(weight)
    columns[:, -model.recurrent :] = 1.0
    weight.register_hook(lambda grad: grad * columns)


def train_layers_only(model, names):
    """Freezes every weight of `model` but those of the convolutions `names` (their names in a
    weights file, e.g. out, out_half)."""
    convs = named_convs(model)
    unknown = [name for name in names if name not in convs]
    if unknown:
        raise SystemExit(f"--train-layers: the model has no layer {', '.join(unknown)} (it has {', '.join(convs)})")
    for p in model.parameters():
        p.requires_grad_(False)
    for name in names:
        for p in convs[name].parameters():
            p.requires_grad_(True)


def run_window(model, rec, objects, burn_in):
    """The frames of a window [B, burn_in + frames, C, H, W] (their object ids `objects` [B, burn_in
    + frames, 1, H, W]) one `step` at a time, the first `burn_in` without gradients; returns the
    outputs of the others [B, frames, 3, H, W]."""
    state = None
    if burn_in:
        with torch.no_grad():
            for t in range(burn_in):
                _, state = model.step(rec[:, t], state, objects=objects[:, t])
    outs = []
    for t in range(burn_in, rec.shape[1]):
        y, state = model.step(rec[:, t], state, objects=objects[:, t])
        outs.append(y)
    return torch.stack(outs, 1)


def main():
    process_start = time.time()
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", required=True)
    ap.add_argument("--minutes", type=float, default=6.0)
    ap.add_argument(
        "--steps",
        type=int,
        default=0,
        help="train this many steps, the learning rate's schedule over them rather than over --minutes "
        "(which still stops a run that takes longer), so that two runs of one recipe take the same steps "
        "(by time they took 657 and 684 on one H200, forty-ninth session); 0 (default): by time",
    )
    ap.add_argument("--batch", type=int, default=8)
    ap.add_argument("--frames", type=int, default=8, help="frames per window with a loss")
    ap.add_argument("--burn-in", type=int, default=0, help="frames before them, no gradients, no loss")
    ap.add_argument(
        "--burn-in-min", type=int, help="draw each step's burn-in from this up to --burn-in (default: fixed)"
    )
    ap.add_argument(
        "--crop",
        type=int,
        help="side of the square tiles windows are cut from (default: the largest the smallest frame holds, "
        "the whole frame of a square dataset)",
    )
    ap.add_argument("--lr", type=float, default=2e-3)
    ap.add_argument("--model", choices=MODELS, default="direct")
    ap.add_argument("--loss", choices=LOSSES, default="l1grad")
    ap.add_argument(
        "--scales",
        type=int,
        default=SCALES,
        help="the kernel decoder's scales, full resolution and each coarser one half the previous",
    )
    ap.add_argument(
        "--widths",
        default=",".join(str(w) for w in WIDTHS),
        help=f"the U-Net's widths, comma-separated: output channels of {', '.join(HIDDEN)}",
    )
    ap.add_argument(
        "--fireflies",
        type=float,
        default=0.0,
        help="training inputs get isolated bright samples the references lack, at this rate a pixel "
        "and frame (data.add_fireflies)",
    )
    ap.add_argument(
        "--weights",
        help="the loss terms' weights, comma-separated: l1grad spatial,gradient,temporal (default "
        "0.8,0.1,0.1); l1msssim l1,msssim,temporal (default 0.16,0.84,0.1); l1gradflip spatial,gradient,"
        "temporal,flip (default 0.8,0.1,0.1,0.5)",
    )
    ap.add_argument(
        "--blotch",
        type=float,
        default=0.0,
        help="weight of the mean worst 8x8 block excess over the reference (losses.worst_block_excess) "
        "added to the loss",
    )
    ap.add_argument(
        "--blotch-margin",
        type=float,
        default=0.0,
        help="the blotch term counts only the excess beyond this (relative to the frame's mean luminance)",
    )
    ap.add_argument(
        "--cold",
        type=float,
        default=0.0,
        help="probability that a window starts at the cut, without burn-in, its frames weighed alike",
    )
    ap.add_argument(
        "--linear-mix",
        action="store_true",
        help="the kernel decoder mixes log-space and linear-space filtering per pixel (kernel_model.py)",
    )
    ap.add_argument(
        "--energy",
        type=float,
        default=0.0,
        help="weight of the light of 8x8 blocks against the reference's (losses.energy_l1) added to the loss",
    )
    ap.add_argument(
        "--history-frames",
        type=int,
        help="the most frames the running means average before they become moving averages "
        f"(1 to {int(N_MAX)}; default: --init's, else {int(N_MAX)})",
    )
    ap.add_argument(
        "--spatial-variance-frames",
        type=int,
        help="the history lengths below which the variance inputs are taken over the 3x3 neighbourhood "
        f"of the frame's samples (0 to {int(N_MAX)}; default: --init's, else 0: never)",
    )
    ap.add_argument(
        "--atrous-steps",
        default="",
        help="the spacings in pixels, comma-separated (e.g. 4,8,16), of the a-trous filter over the output "
        "that a gate the network predicts blends in per pixel (model.atrous; default: --init's, else none)",
    )
    ap.add_argument(
        "--recurrent",
        type=int,
        help="channels of recurrent state the network writes at full resolution and reads, warped, in the next "
        "frame beside its input features (model.RecurrentDenoiser; default: --init's, else none; weights "
        "without it start it with enc0's weights for it at zero and the layer writing it afresh)",
    )
    ap.add_argument(
        "--motion-inputs",
        action="store_true",
        help="enc0 also reads the reprojection's motion (model.motion_inputs: its length and how much its "
        "bilinear taps blur); default: --init's; weights without it start with enc0's weights for it at zero",
    )
    ap.add_argument(
        "--noise-inputs",
        action="store_true",
        help="enc0 also reads the running means' own noise (model.noise_inputs: their deviations over "
        "sqrt(history length)); default: --init's; weights without it start with enc0's weights for it at zero",
    )
    ap.add_argument(
        "--gate-only",
        action="store_true",
        help="train only the gate of the a-trous filter (out's last channel), every other weight kept as --init's",
    )
    ap.add_argument(
        "--state-only",
        action="store_true",
        help="train only the recurrent state: its layer and enc0's weights reading it, every other weight "
        "kept as --init's (with --recurrent)",
    )
    ap.add_argument(
        "--train-layers",
        default="",
        help="train only these layers (comma-separated names of the weights file, e.g. out,out_half), "
        "every other weight kept as --init's",
    )
    ap.add_argument("--val-every", type=int, default=250, help="validate every this many steps")
    ap.add_argument(
        "--watch",
        default="",
        help="scenes of the training split (comma-separated, e.g. covered-light) also validated on "
        "their own whenever the validation sequences are: a failure case to keep an eye on",
    )
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--init", help="start from these weights (a file train.py wrote)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--log", required=True)
    args = ap.parse_args()
    if args.steps < 0:
        raise SystemExit(f"--steps {args.steps} is negative")
    group = Group()
    torch.manual_seed(args.seed)
    dev = group.device
    train = load_split(args.data, "train", dev, part=group.share())
    val = load_split(args.data, "validation", dev) if group.first else []
    watch = watched(args.data, args.watch, dev) if group.first else []
    burn_in_min = args.burn_in if args.burn_in_min is None else args.burn_in_min
    if not 0 <= burn_in_min <= args.burn_in:
        raise SystemExit(f"--burn-in-min {burn_in_min} is not between 0 and --burn-in {args.burn_in}")
    window = args.burn_in + args.frames
    shortest = min(s["record"].shape[0] for s in train)
    if window > shortest:
        raise SystemExit(f"--burn-in {args.burn_in} + --frames {args.frames} > {shortest}, the shortest sequence")
    smallest = min(min(s["record"].shape[-2:]) for s in train)
    args.crop = args.crop or smallest
    if not 0 < args.crop <= smallest:
        raise SystemExit(f"--crop {args.crop} is not between 1 and {smallest}, the smallest frame's side")
    widths = tuple(int(w) for w in args.widths.split(","))
    if len(widths) != len(HIDDEN) or any(w <= 0 or w % 16 for w in widths):
        raise SystemExit(f"--widths takes {len(HIDDEN)} multiples of 16")
    if args.linear_mix and args.model != "kernel":
        raise SystemExit("--linear-mix is the kernel decoder's (--model kernel)")
    if args.init and args.model == "kernel" and file_linear_mix(args.init):
        args.linear_mix = True
    try:
        atrous_steps = atrous_steps_of(args.atrous_steps)
    except ValueError as e:
        raise SystemExit(f"--atrous-steps: {e}") from None
    init_steps = file_atrous_steps(args.init) if args.init else ()
    if init_steps and atrous_steps and atrous_steps != init_steps:
        steps = ",".join(str(s) for s in init_steps)
        raise SystemExit(f"--atrous-steps {args.atrous_steps}: --init {args.init} has the gate of steps {steps}")
    atrous_steps = init_steps or atrous_steps
    init_recurrent = file_recurrent(args.init) if args.init else 0
    if args.recurrent is not None and (args.recurrent < 0 or init_recurrent not in (0, args.recurrent)):
        raise SystemExit(f"--recurrent {args.recurrent}: --init {args.init} has {init_recurrent} channels of it")
    recurrent = init_recurrent if args.recurrent is None else args.recurrent
    wanted = [name for name, on in (("motion", args.motion_inputs), ("noise", args.noise_inputs)) if on]
    extras = extras_of(set(wanted) | set(file_extras(args.init) if args.init else ()))
    model = build_model(args.model, widths, args.scales, args.linear_mix, atrous_steps, recurrent, extras).to(dev)
    if args.init:
        load_weights(model, args.init)
    if args.history_frames is not None:
        if not 1 <= args.history_frames <= N_MAX:
            raise SystemExit(f"--history-frames {args.history_frames} is not between 1 and {int(N_MAX)}")
        model.history_frames = args.history_frames
    if args.spatial_variance_frames is not None:
        if not 0 <= args.spatial_variance_frames <= N_MAX:
            raise SystemExit(f"--spatial-variance-frames {args.spatial_variance_frames} is not between 0 and {int(N_MAX)}")
        model.spatial_variance_frames = args.spatial_variance_frames
    if args.gate_only:
        if not model.gate or not args.init:
            raise SystemExit("--gate-only trains the gate of --init's model: give --init and --atrous-steps (or a gated --init)")
        train_gate_only(model)
    if args.state_only:
        if not args.init or not model.recurrent or args.gate_only:
            raise SystemExit(
                "--state-only trains the recurrent state added to --init's model: give --init and --recurrent, "
                "without --gate-only"
            )
        train_state_only(model)
    train_layers = [name for name in args.train_layers.split(",") if name]
    if train_layers:
        if not args.init or args.gate_only or args.state_only:
            raise SystemExit("--train-layers trains layers of --init's model, and not with --gate-only or --state-only")
        train_layers_only(model, train_layers)
    group.same_start(model)
    cost = model_cost(model, dev)
    if group.first:
        head = {"model": args.model, "loss": args.loss, "device": dev, "processes": group.world, **cost}
        print(json.dumps(head), flush=True)
    opt = torch.optim.Adam([p for p in model.parameters() if p.requires_grad], lr=args.lr)
    ws = [float(v) for v in args.weights.split(",")] if args.weights else list(DEFAULT_WEIGHTS[args.loss])
    if len(ws) != len(TERM_NAMES[args.loss]):
        raise SystemExit(f"--weights takes {len(TERM_NAMES[args.loss])} numbers for --loss {args.loss}")
    compute_loss = loss_fn(args.loss)
    autocast = (lambda: torch.autocast("cuda", dtype=torch.bfloat16)) if dev == "cuda" else contextlib.nullcontext
    # Each process its own windows: the first draws what a single process would.
    seed = args.seed + PROCESS_SEED_STRIDE * group.rank
    gen = torch.Generator().manual_seed(seed)
    # Its own generator, so that the same seed draws the same windows with or without fireflies; on
    # the training device (drawn on the CPU, they took half the steps).
    firefly_gen = torch.Generator(dev).manual_seed(seed + 1)
    budget = args.minutes * 60.0
    start = time.time()
    history, step, skipped = [], 0, 0
    while True:
        elapsed = group.progress((time.time() - start) / budget)
        frac = step / args.steps if args.steps > 0 else elapsed
        if frac >= 1.0 or elapsed >= 1.0:
            break
        for param_group in opt.param_groups:
            param_group["lr"] = args.lr * 0.5 * (1.0 + math.cos(math.pi * frac))
        cold = bool(torch.rand((), generator=gen) < args.cold)
        burn_in = 0 if cold else int(torch.randint(burn_in_min, args.burn_in + 1, (1,), generator=gen))
        rec, ref, objects = sample_batch(train, args.batch, burn_in + args.frames, args.crop, gen)
        rec, ref, objects = rec.to(dev), ref[:, burn_in:].to(dev), objects.to(dev)
        if args.fireflies:
            rec[:, :, 0:3] = add_fireflies(rec[:, :, 0:3], args.fireflies, firefly_gen)
        with autocast():
            out = run_window(model, rec, objects, burn_in)
        out = out.float()
        loss, terms = compute_loss(out, ref, ws, flat=cold)
        if args.blotch:
            excess = worst_block_excess(out.flatten(0, 1), ref.flatten(0, 1))
            blotch = (excess - args.blotch_margin).clamp_min(0.0).mean()
            loss = loss + args.blotch * blotch
            terms = (*terms, blotch)
        if args.energy:
            energy = energy_l1(out.flatten(0, 1), ref.flatten(0, 1))
            loss = loss + args.energy * energy
            terms = (*terms, energy)
        if not group.all_finite(loss):
            # A window that breaks the arithmetic (a non-finite input, an overflow) must not poison
            # the weights.
            skipped += 1
            if skipped > max(10, step // 100):
                raise SystemExit(f"{skipped} non-finite losses in {step + skipped} steps: stopping")
            continue
        opt.zero_grad(set_to_none=True)
        loss.backward()
        group.average_gradients(model)
        torch.nn.utils.clip_grad_norm_(model.parameters(), 1.0)
        opt.step()
        step += 1
        if step % args.val_every == 0 and group.first:
            entry = {"step": step, "seconds": round(time.time() - start, 1), "loss": loss.item()}
            names = TERM_NAMES[args.loss] + (("blotch",) if args.blotch else ()) + (("energy",) if args.energy else ())
            entry["loss_terms"] = {k: round(v.item(), 6) for k, v in zip(names, terms)}
            entry.update(validation(model, val, watch))
            history.append(entry)
            print(json.dumps(entry), flush=True)
    train_seconds = time.time() - start
    if not group.first:
        group.wait()
        group.close()
        return
    final = validation(model, val, watch)
    if isinstance(model, KernelDenoiser):
        layers = kernel_layers(model.widths, model.scales, model.linear_mix, model.gate, model.recurrent, model.extras)
        tensors = kernel_export_tensors(model)
    else:
        layers, tensors = model.layers, export_tensors(model)
    fmt = FORMAT
    meta = {
        "format": fmt,
        "decoder": args.model,
        "layers": json.dumps(layers),
        "model": args.model,
        "loss": args.loss,
        "loss_weights": ",".join(str(w) for w in ws),
        "emission_motion": str(model.emission_motion),
        "history_frames": str(model.history_frames),
        "spatial_variance_frames": str(model.spatial_variance_frames),
        "burn_in": str(args.burn_in) if burn_in_min == args.burn_in else f"{burn_in_min}-{args.burn_in}",
        "fireflies": str(args.fireflies),
        "blotch": str(args.blotch),
        "blotch_margin": str(args.blotch_margin),
        "cold": str(args.cold),
        "energy": str(args.energy),
        "gate_only": str(args.gate_only),
        "state_only": str(args.state_only),
        "train_layers": args.train_layers,
        "crop": str(args.crop),
        "batch": str(args.batch),
        "steps": str(step),
        "processes": str(group.world),
        "data": args.data,
        "init": args.init or "",
        "validation_relmse": f"{final['relmse']:.5f}",
        "validation_ssim": f"{final['ssim']:.5f}",
        "validation_flip": f"{final['flip']:.5f}",
        "validation_temporal": f"{final['temporal']:.5f}",
        "validation_blotch": f"{final['blotch']:.5f}",
        "validation_light": f"{final['light']:.5f}",
        "watch": json.dumps({"scenes": args.watch, **final["watch"]}) if watch else "",
    }
    if model.atrous_steps:
        meta["atrous_steps"] = ",".join(str(s) for s in model.atrous_steps)
    for name in model.extras:
        meta[f"{name}_inputs"] = str(EXTRA_INPUTS[name])
    save_file(tensors, args.out, metadata=meta)
    summary = {
        "final": final,
        "steps": step,
        "processes": group.world,
        "skipped_steps": skipped,
        "train_seconds": round(train_seconds, 1),
        "total_seconds": round(time.time() - process_start, 1),
        "device": torch.cuda.get_device_name() if str(dev).startswith("cuda") else "cpu",
        **cost,
    }
    with open(args.log, "w") as f:
        json.dump({"args": vars(args), "format": fmt, "loss_weights": ws, **summary, "history": history}, f, indent=1)
    print(json.dumps(summary), flush=True)
    group.wait()
    group.close()


if __name__ == "__main__":
    main()
