"""What the Mitsuba 3 scripts here share: the command-line size, the GPU's name and driver, and
Mitsuba's own Cornell box set up as Lucid's `cornell-box` renders it (box reconstruction filter,
`path` integrator, `independent` sampler, the scene's camera: `fov` 39.3077 deg along
`fov_axis` = 'smaller')."""

import argparse
import subprocess


def parse_size(s):
    try:
        w, h = s.lower().split('x')
        return int(w), int(h)
    except ValueError:
        raise argparse.ArgumentTypeError('size must be WxH, e.g. 1920x1080')


def gpu_info():
    """(name, driver) of GPU 0 via nvidia-smi, or (None, None)."""
    try:
        r = subprocess.run(['nvidia-smi', '--query-gpu=name,driver_version',
                            '--format=csv,noheader'],
                           capture_output=True, text=True, timeout=20)
        line = r.stdout.strip().splitlines()[0]
        name, driver = [x.strip() for x in line.split(',', 1)]
        return name, driver
    except Exception:
        return None, None


def cornell_box(mi, size, max_depth, spp_per_call):
    """`mitsuba.cornell_box()` at `size` (W, H), box filter, `path` integrator of `max_depth`
    (Mitsuba's convention, Lucid's too), `spp_per_call` samples per render call. Returns the
    scene dictionary (load it with `mi.load_dict`)."""
    s = mi.cornell_box()
    film = s['sensor']['film']
    film['width'], film['height'] = size
    film['rfilter'] = {'type': 'box'}
    s['sensor']['sampler'] = {'type': 'independent', 'sample_count': spp_per_call}
    s['integrator'] = {'type': 'path', 'max_depth': max_depth}
    return s


def render(mi, dr, scene, seed, spp, spp_per_call):
    """The mean of `spp` samples per pixel rendered in calls of at most `spp_per_call` (one
    wavefront of 1920x1080x64 fits; 1024 would not), forced to completion. Call k of `seed` uses
    Mitsuba's seed `seed * 4096 + k`: distinct seeds give independent images (seeds below 2^20
    stay within Mitsuba's 32-bit seed)."""
    img, done, call = None, 0, 0
    while done < spp:
        n = min(spp_per_call, spp - done)
        part = mi.render(scene, seed=seed * 4096 + call, spp=n) * (n / spp)
        img = part if img is None else img + part
        dr.eval(img)
        done += n
        call += 1
    dr.sync_thread()
    return img
