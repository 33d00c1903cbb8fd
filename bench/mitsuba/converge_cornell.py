#!/usr/bin/env python3
"""Mitsuba 3's error-against-time series on its Cornell box, for `lucid converge --external`.

Renders `mitsuba.cornell_box()` (set up as `cornell.py` says: Lucid's `cornell-box` is its
transcription) at each of `--spp` samples per pixel and times each render (wall time from the
call to the image's completion, `dr.sync_thread()`; the median of `--runs` after a warm-up
render at that sample count, which compiles its kernels), then renders the reference at
`--reference-spp` with other seeds. Writes into `--out`:

- `mitsuba_<spp>.exr`: each sample count's image (the last timed run's), linear RGB;
- `reference.exr`: the reference, the one both renderers are measured against;
- `series.json`: `{"name", "renderer", "device", "time": "wall", "points": [{"spp", "ms",
  "image"}], "reference": {"spp", "image"}, ...}`, the format `lucid converge --external`
  reads (image paths relative to the file).

Lucid then measures both renderers' errors with the same metrics against the same reference:

    PYTHONPATH=/tmp/mitsuba python3 bench/mitsuba/converge_cornell.py --out /tmp/mi
    lucid converge --scene cornell-box --size 1920x1080 --algos pt --denoisers none \
        --spp 1,16 --reference /tmp/mi/reference.exr --external "Mitsuba 3"=/tmp/mi/series.json
"""

import argparse
import json
import os
import platform
import statistics
import time

from cornell import cornell_box, gpu_info, parse_size, render


def spp_list(s):
    try:
        values = [int(v) for v in s.split(',')]
    except ValueError:
        raise argparse.ArgumentTypeError('samples per pixel: comma-separated integers')
    if not values or min(values) < 1:
        raise argparse.ArgumentTypeError('samples per pixel must be at least 1')
    return values


def main():
    ap = argparse.ArgumentParser(description="Mitsuba 3's error-against-time series (Cornell box)")
    ap.add_argument('--variant', default='cuda_ad_rgb')
    ap.add_argument('--size', type=parse_size, default=(1920, 1080))
    ap.add_argument('--spp', type=spp_list, default=spp_list('16,32,64,128,256,512,1024'))
    ap.add_argument('--reference-spp', type=int, default=8192)
    ap.add_argument('--spp-per-call', type=int, default=64,
                    help='samples per pixel per render call (a 1920x1080x64 wavefront fits)')
    ap.add_argument('--max-depth', type=int, default=8)
    ap.add_argument('--runs', type=int, default=3, help='timed renders per sample count (median)')
    ap.add_argument('--out', required=True, help='output folder')
    args = ap.parse_args()

    import drjit as dr
    import mitsuba as mi
    mi.set_variant(args.variant)
    os.makedirs(args.out, exist_ok=True)
    scene = mi.load_dict(cornell_box(mi, args.size, args.max_depth, args.spp_per_call))

    points = []
    for spp in args.spp:
        render(mi, dr, scene, 1, spp, args.spp_per_call)
        times = []
        for run in range(args.runs):
            started = time.perf_counter()
            img = render(mi, dr, scene, 2 + run, spp, args.spp_per_call)
            times.append(time.perf_counter() - started)
        image = 'mitsuba_%d.exr' % spp
        mi.Bitmap(img).write(os.path.join(args.out, image))
        ms = statistics.median(times) * 1e3
        points.append({'spp': spp, 'ms': ms, 'times_ms': [t * 1e3 for t in times], 'image': image})
        print('%5d spp: %9.2f ms (median of %d)' % (spp, ms, args.runs), flush=True)

    started = time.perf_counter()
    reference = render(mi, dr, scene, 100_000, args.reference_spp, args.spp_per_call)
    mi.Bitmap(reference).write(os.path.join(args.out, 'reference.exr'))
    print('reference: %d spp in %.1f s' % (args.reference_spp, time.perf_counter() - started))

    name, driver = gpu_info() if args.variant.startswith('cuda') else (None, None)
    series = {
        'name': 'Mitsuba 3',
        'renderer': 'Mitsuba %s %s (Dr.Jit %s)' % (mi.__version__, args.variant, dr.__version__),
        'device': name or platform.processor() or 'CPU',
        'driver': driver,
        'time': 'wall',
        'scene': 'mitsuba.cornell_box(), box filter, path integrator',
        'size': list(args.size),
        'max_depth': args.max_depth,
        'spp_per_call': args.spp_per_call,
        'points': points,
        'reference': {'spp': args.reference_spp, 'image': 'reference.exr'},
    }
    with open(os.path.join(args.out, 'series.json'), 'w') as f:
        json.dump(series, f, indent=1)
        f.write('\n')
    print('wrote', os.path.join(args.out, 'series.json'))


if __name__ == '__main__':
    main()
