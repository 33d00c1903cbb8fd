#!/usr/bin/env python3
"""Mitsuba 3 GPU throughput benchmark on its built-in Cornell box, to compare
with Lucid.

Renders ``mitsuba.cornell_box()`` modified to WxH (default 1920x1080), box
reconstruction filter, ``path`` integrator with ``max_depth`` = 8 (Mitsuba's
convention: 1 = emitted light only, 2 = direct illumination, ...; Lucid uses
the same), ``independent`` sampler, default 64 spp.  The camera keeps the
scene's ``fov`` = 39.3077 deg along ``fov_axis`` = 'smaller' (i.e. vertical for
a landscape film).

One warm-up render (JIT compilation, OptiX pipeline build, kernel cache), then
N timed renders; each timed render is forced to completion (``dr.eval`` of the
image + ``dr.sync_thread()``) before the clock stops.  Reports best and median
time and paths/s = W*H*spp / time.

Mitsuba is not imported from site-packages: set PYTHONPATH to the directory
unpacked from mitsuba-py312.tar.xz (see README.md).

    PYTHONPATH=/tmp/mitsuba python3 bench_cornell.py --out mitsuba_cornell.json
    PYTHONPATH=... python3 bench_cornell.py --variant scalar_rgb --size 64x36 --spp 4
"""

import argparse
import json
import os
import platform
import statistics
import sys
import time

from cornell import cornell_box, gpu_info, parse_size, render


def main():
    ap = argparse.ArgumentParser(description='Mitsuba 3 Cornell box GPU benchmark')
    ap.add_argument('--variant', default='cuda_ad_rgb')
    ap.add_argument('--size', type=parse_size, default=(1920, 1080),
                    help='WxH (default 1920x1080)')
    ap.add_argument('--spp', type=int, default=64)
    ap.add_argument('--max-depth', type=int, default=8)
    ap.add_argument('--runs', type=int, default=5, help='timed runs (best-of-N)')
    ap.add_argument('--seed', type=int, default=0)
    ap.add_argument('--passes', type=int, default=1,
                    help='split the spp into this many render calls per timed '
                         'run (only if one 64-spp wavefront does not fit in memory)')
    ap.add_argument('--save', default=None,
                    help='optionally write the last image (e.g. out.exr)')
    ap.add_argument('--out', default=None, help='write results JSON here')
    args = ap.parse_args()

    import drjit as dr
    import mitsuba as mi
    mi.set_variant(args.variant)

    W, H = args.size
    if args.spp % args.passes:
        sys.exit('--spp must be divisible by --passes')
    spp_pass = args.spp // args.passes

    s = cornell_box(mi, (W, H), args.max_depth, spp_pass)
    fov_axis = s['sensor'].get('fov_axis', 'x')

    t = time.perf_counter()
    scene = mi.load_dict(s)
    load_s = time.perf_counter() - t

    def render_once(seed):
        return render(mi, dr, scene, seed, args.spp, spp_pass)

    t = time.perf_counter()
    img = render_once(args.seed)
    warm_s = time.perf_counter() - t
    print('warm-up (incl. JIT compile): %.3f s' % warm_s, flush=True)

    times = []
    for i in range(args.runs):
        dr.sync_thread()
        t = time.perf_counter()
        img = render_once(args.seed)
        dt = time.perf_counter() - t
        times.append(dt)
        print('run %d: %.4f s  (%.3f Mpaths/s)' % (
            i + 1, dt, W * H * args.spp / dt / 1e6), flush=True)

    # Sanity: the image mean (forces a host read-back too).
    try:
        mean = [float(x) for x in dr.mean(img, axis=(0, 1)).array]
    except Exception as e:  # not essential
        print('image mean unavailable:', e)
        mean = None

    if args.save:
        os.makedirs(os.path.dirname(os.path.abspath(args.save)), exist_ok=True)
        mi.Bitmap(img).write(args.save)

    best, med = min(times), statistics.median(times)
    paths = W * H * args.spp
    name, driver = gpu_info() if args.variant.startswith('cuda') else (None, None)
    res = {
        'renderer': 'mitsuba',
        'mitsuba_version': mi.__version__,
        'drjit_version': dr.__version__,
        'variant': args.variant,
        'scene': 'mitsuba.cornell_box()',
        'width': W, 'height': H, 'resolution': '%dx%d' % (W, H),
        'spp': args.spp, 'passes': args.passes,
        'max_depth': args.max_depth,
        'integrator': 'path', 'rfilter': 'box', 'sampler': 'independent',
        'fov_axis': fov_axis,
        'scene_load_s': load_s,
        'warmup_s': warm_s,
        'times_s': times,
        'best_s': best,
        'median_s': med,
        'paths': paths,
        'paths_per_s_best': paths / best,
        'paths_per_s_median': paths / med,
        'image_mean_rgb': mean,
        'gpu_name': name,
        'nvidia_driver': driver,
        'python': platform.python_version(),
        'host': platform.node(),
    }
    if args.variant.startswith('cuda'):
        try:
            res['cuda_version'] = str(dr.detail.cuda_version())
            res['cuda_compute_capability'] = dr.detail.cuda_compute_capability()
        except Exception:
            pass
    print('%s %dx%d %d spp max_depth %d: best %.4f s, median %.4f s, '
          '%.3f / %.3f Mpaths/s (best/median) on %s' % (
              args.variant, W, H, args.spp, args.max_depth, best, med,
              paths / best / 1e6, paths / med / 1e6, name or platform.processor() or 'CPU'))
    if args.out:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        with open(args.out, 'w') as f:
            json.dump(res, f, indent=2)
            f.write('\n')
        print('wrote', args.out)


if __name__ == '__main__':
    main()
