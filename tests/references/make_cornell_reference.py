#!/usr/bin/env python3
"""Mitsuba 3 reference render of Mitsuba's built-in Cornell box, for Lucid's
frame-capture correctness test.

Scene: ``mitsuba.cornell_box()`` (the scene dict shipped with Mitsuba 3), with
these changes only:

* film: 256x256 ``hdrfilm``, RGB float32, linear, ``rfilter`` = ``box``
  (each sample lands in exactly one pixel, so pixels are independent);
* integrator: ``path`` with ``max_depth`` = 8;
* sampler: ``independent``, several independent passes with fixed seeds,
  averaged.

Depth convention (``max_depth``), Mitsuba's definition -- Lucid uses the SAME
definition:

* ``max_depth = 1``: only emitted light seen directly by the camera;
* ``max_depth = 2``: direct illumination (one bounce: camera -> surface ->
  light, via emission hit or next-event estimation);
* ``max_depth = k``: paths of at most ``k`` segments (vertices after the
  camera), i.e. ``k - 1`` scattering events;
* ``max_depth = -1``: unbounded (Russian roulette only).

Mitsuba's ``path`` integrator also uses Russian roulette from depth
``rr_depth`` = 5 on (unbiased, so it does not change the expectation).

Outputs (next to this script):

* ``cornell_box_mitsuba_256.exr``  -- mean of all passes, RGB float32, linear,
  row 0 = top of the image (lossless PIZ compression);
* ``cornell_box_mitsuba_256.json`` -- spp, seeds, mitsuba version, max_depth,
  render time, image mean per channel, noise estimates (see below);
* ``cornell_box_mitsuba_scene.txt`` -- dump of the exact scene dict.

Noise estimates in the JSON (computed from the spread of the P passes, each
with S spp; the reference has N = P*S spp):

* ``ref_pixel_var_mean[c]``: per-pixel variance of the *reference image*
  itself, averaged over pixels (= pass variance / P);
* ``per_sample_pixel_var_mean[c]``: per-pixel variance of a 1-spp estimate,
  averaged over pixels (= pass variance * S).  A Mitsuba-equivalent renderer at
  n spp has an expected per-pixel variance of about this / n, so the expected
  mean squared difference of such an image to the reference is about
  ``per_sample_pixel_var_mean * (1/n + 1/N)``;
* ``image_mean_rel_stderr[c]``: relative standard error of the image mean.

Usage:  python3 make_cornell_reference.py [--passes 32] [--spp-per-pass 512]
                                         [--time-budget-s 1380]
Timing on an idle 2-core x86 machine (scalar_rgb): ~0.054 s per spp at
256x256 (16384 spp ~ 15 min).  The machine may be shared, so passes stop once
the time budget would be exceeded; the JSON records the spp actually rendered.
Seeds are BASE_SEED + pass index; Mitsuba's scalar renderer derives a distinct
per-pixel seed (seed * W*H + pixel), so passes are independent.
"""

import argparse
import json
import os
import pprint
import time

import numpy as np
import mitsuba as mi

HERE = os.path.dirname(os.path.abspath(__file__))
MAX_DEPTH = 8
RES = 256
BASE_SEED = 20240601


def scene_dict(spp):
    s = mi.cornell_box()
    film = s['sensor']['film']
    film['width'] = RES
    film['height'] = RES
    film['rfilter'] = {'type': 'box'}
    film['pixel_format'] = 'rgb'
    film['component_format'] = 'float32'
    s['sensor']['sampler'] = {'type': 'independent', 'sample_count': spp}
    s['integrator'] = {'type': 'path', 'max_depth': MAX_DEPTH}
    return s


SCENE_NOTES = """\
Notes (Mitsuba 3 conventions):
* 'rectangle': the square [-1,1]^2 in the local XY plane (z = 0), normal +Z,
  before to_world.  'cube': the box [-1,1]^3 before to_world (12 triangles,
  outward normals).  Points transform by to_world (the 'matrix' above, column
  vectors, last column = translation); normals by 'inverse_transpose'.
* All BSDFs are 'diffuse' (Lambertian) with the given RGB 'reflectance'.
  Mitsuba BSDFs are ONE-SIDED: a ray hitting the back side (the side opposite
  the geometric/shading normal) sees a black surface (no 'twosided' wrapper
  is used here).  Every wall/box face seen in this scene is hit from its
  front side: back +Z, floor +Y, ceiling -Y, red wall (x=-1) +X, green wall
  (x=+1) -X, cube faces outward.
* 'light' is a rectangle with an 'area' emitter (constant 'radiance', RGB,
  one-sided: emits only on the +Z side of the local rectangle, i.e. along
  to_world * (0,0,1) = (0,-1,0), downward) and the 'white' BSDF.
* Sensor 'perspective': camera looks along local +Z, local +Y is up, local +X
  is image LEFT (Mitsuba's look_at builds columns [left, up, dir, origin]).
  Here to_world maps it to origin (0,0,3.9) looking along -Z, up +Y, image
  left = world -X, so the red wall (x = -1) appears on the left.
  'fov' = 39.3077 degrees measured along 'fov_axis' = 'smaller' (the smaller
  image dimension; for the square 256x256 film this equals both 'x' and 'y'.
  Mitsuba's own default when fov_axis is absent is 'x').
  near_clip 0.001, far_clip 100 (no geometry is near either).
* Film pixel (0,0) is the top-left pixel; image row 0 is the top.
* Reference overrides: film 256x256, rfilter box, integrator path
  max_depth 8 (1 = emitted light only, 2 = direct illumination, ...),
  sampler independent.
"""


def dump_scene(path, version):
    s = mi.cornell_box()
    with open(path, 'w') as f:
        f.write('# mitsuba.cornell_box() as returned by mitsuba %s '
                '(variant scalar_rgb), unmodified\n\n' % version)
        f.write(pprint.pformat(s, width=100))
        f.write('\n\n')
        # Plain matrices, easier to copy into Rust.
        f.write('# to_world matrices (row-major 4x4, column-vector convention)\n')
        for name in sorted(s):
            v = s[name]
            if isinstance(v, dict) and 'to_world' in v:
                m = np.array(v['to_world'].matrix, dtype=np.float64)
                f.write('%s (%s):\n' % (name, v.get('type')))
                for row in m:
                    f.write('  [%s]\n' % ', '.join('% .9g' % x for x in row))
        f.write('\n')
        f.write(SCENE_NOTES)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--passes', type=int, default=32,
                    help='maximum number of passes')
    ap.add_argument('--spp-per-pass', type=int, default=512)
    ap.add_argument('--time-budget-s', type=float, default=1380.0,
                    help='stop starting new passes when the next one would '
                         'end after this many seconds (at least --min-passes '
                         'are always rendered)')
    ap.add_argument('--min-passes', type=int, default=4)
    ap.add_argument('--out-dir', default=HERE)
    ap.add_argument('--dump-only', action='store_true',
                    help='only write the scene dump')
    args = ap.parse_args()

    mi.set_variant('scalar_rgb')
    version = mi.__version__
    os.makedirs(args.out_dir, exist_ok=True)
    dump_scene(os.path.join(args.out_dir, 'cornell_box_mitsuba_scene.txt'), version)
    if args.dump_only:
        return

    S, P = args.spp_per_pass, args.passes
    scene = mi.load_dict(scene_dict(S))
    seeds = []
    passes = []
    t0 = time.time()
    last = 0.0
    for i in range(P):
        elapsed = time.time() - t0
        if i >= args.min_passes and elapsed + 1.05 * last > args.time_budget_s:
            print('time budget reached after %d passes (%.0f s)' % (i, elapsed))
            break
        seed = BASE_SEED + i
        seeds.append(seed)
        tp = time.time()
        img = np.array(mi.render(scene, seed=seed, spp=S), dtype=np.float64)
        passes.append(img[..., :3])
        last = time.time() - tp
        print('pass %d/%d seed %d: %.1f s, mean %s' % (
            i + 1, P, seed, last, img[..., :3].mean(axis=(0, 1))),
            flush=True)
    render_time = time.time() - t0
    P = len(passes)

    stack = np.stack(passes)                      # P x H x W x 3
    mean = stack.mean(axis=0)                     # reference image
    pass_var = stack.var(axis=0, ddof=1)          # per-pixel variance of one pass
    ref_var = pass_var / P                        # ... of the reference
    per_sample_var = pass_var * S                 # ... of a 1-spp estimate
    pass_means = stack.mean(axis=(1, 2))          # P x 3
    img_mean = mean.mean(axis=(0, 1))
    img_mean_se = pass_means.std(axis=0, ddof=1) / np.sqrt(P)

    exr = os.path.join(args.out_dir, 'cornell_box_mitsuba_%d.exr' % RES)
    bmp = mi.Bitmap(np.ascontiguousarray(mean.astype(np.float32)),
                    pixel_format=mi.Bitmap.PixelFormat.RGB)
    bmp.write(exr)

    def lst(a):
        return [float(x) for x in a]

    meta = {
        'renderer': 'mitsuba',
        'mitsuba_version': version,
        'drjit_version': __import__('drjit').__version__,
        'variant': 'scalar_rgb',
        'scene': 'mitsuba.cornell_box() with film %dx%d, rfilter box, '
                 'integrator path, independent sampler' % (RES, RES),
        'width': RES,
        'height': RES,
        'rfilter': 'box',
        'integrator': 'path',
        'max_depth': MAX_DEPTH,
        'max_depth_convention': '1 = emitted light seen directly only, '
                                '2 = direct illumination, ... (Mitsuba; same in Lucid)',
        'sampler': 'independent',
        'spp': S * P,
        'passes': P,
        'spp_per_pass': S,
        'seeds': seeds,
        'render_time_s': round(render_time, 2),
        'exr': os.path.basename(exr),
        'exr_format': 'RGB float32, linear, row 0 = top',
        'image_mean': lst(img_mean),
        'image_mean_stderr': lst(img_mean_se),
        'image_mean_rel_stderr': lst(img_mean_se / img_mean),
        'ref_pixel_var_mean': lst(ref_var.mean(axis=(0, 1))),
        'ref_pixel_rel_std_rms': lst(np.sqrt(ref_var.mean(axis=(0, 1))) / img_mean),
        'per_sample_pixel_var_mean': lst(per_sample_var.mean(axis=(0, 1))),
        'per_sample_pixel_var_median': lst(np.median(per_sample_var, axis=(0, 1))),
        'noise_note': 'ref_pixel_var_mean: per-pixel variance of the reference '
                      'image averaged over pixels (pass variance / passes). '
                      'per_sample_pixel_var_mean: same for a 1-spp estimate; an '
                      'n-spp render differs from the reference by a per-pixel MSE '
                      'of about per_sample_pixel_var_mean*(1/n + 1/spp).',
    }
    with open(os.path.join(args.out_dir, 'cornell_box_mitsuba_%d.json' % RES), 'w') as f:
        json.dump(meta, f, indent=2)
        f.write('\n')
    print(json.dumps(meta, indent=2))


if __name__ == '__main__':
    main()
