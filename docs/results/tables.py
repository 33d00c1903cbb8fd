"""Writes the results page (markdown, to stdout) from what `generate.sh` measured in OUT_DIR:

    python3 docs/results/tables.py OUT_DIR > OUT_DIR/README.md

Frame times per scene and algorithm (the study's Table 4.1), the denoisers' times per size
(Table 4.2), DSSIM at the study's accumulated times per configuration (Table 4.3), each
configuration's time to converge, links to `lucid converge`'s charts, and the device and commands.
Python's standard library only.
"""

import json
import math
import sys
from pathlib import Path

# The study's Table 4.3 times, in GPU milliseconds (20 ms to 1.3 s of accumulation).
CHECKPOINTS_MS = (20.0, 161.0, 343.0, 1292.0)

# The study's own measurements (RTX 2070, path depth 32, OptiX denoiser), beside Lucid's built-in
# scene that is the analogue of its scene. Table 4.1: (PT ms, BDPT ms) per scene and size.
STUDY = "the study (RTX 2070, depth 32)"
STUDY_SCENES = {
    "cornell-teapot": "Teapot Cornell Box",
    "covered-light": "Covered Dragon",
    "blinds-room": "Breakfast Room",
    "classroom": "Japanese Classroom",
}
STUDY_FRAME_MS = {
    ("cornell-teapot", "1280x720"): (2.3, 9.6),
    ("covered-light", "1280x720"): (4.6, 11.3),
    ("blinds-room", "1280x720"): (2.9, 8.5),
    ("classroom", "1280x720"): (9.3, 22.2),
    ("cornell-teapot", "1920x1080"): (4.8, 16.7),
    ("covered-light", "1920x1080"): (9.5, 24.4),
    ("blinds-room", "1920x1080"): (6.3, 18.6),
    ("classroom", "1920x1080"): (20.2, 52.4),
}
# Table 4.2: OptiX's time per size.
STUDY_DENOISER_MS = {"640x360": 2.8, "854x480": 4.4, "1280x720": 7.5, "1920x1080": 14.5}
# Table 4.3 ("Japanese Classroom"): per configuration, (DSSIM, accumulated samples, seconds) at
# the checkpoints (BDPT's first sample took 0.048 s).
STUDY_CLASSROOM_DSSIM = {
    "pt/none": [(3.06367398, 1, 0.02), (1.26624604, 8, 0.161), (0.96657428, 16, 0.343), (0.64997775, 64, 1.292)],
    "pt/optix": [(0.65222797, 1, 0.02), (0.28258904, 8, 0.161), (0.16146306, 16, 0.343), (0.05030262, 64, 1.292)],
    "bdpt/none": [(2.62315406, 1, 0.048), (1.67064845, 4, 0.161), (1.32711299, 7, 0.343), (0.96057530, 25, 1.292)],
    "bdpt/optix": [(0.71196505, 1, 0.048), (0.49393342, 4, 0.161), (0.32785179, 7, 0.343), (0.15214008, 25, 1.292)],
}


def load(path):
    return json.loads(path.read_text())


def size_key(size):
    w, h = size.split("x")
    return int(w) * int(h)


def median(entry):
    return entry["median"] if isinstance(entry, dict) else float(entry)


def frame_table(out, scenes):
    rows, sizes, algos = {}, set(), set()
    for scene in scenes:
        for f in sorted((out / scene).glob("bench_*_*.json")):
            _, algo, size = f.stem.split("_", 2)
            rows[(scene, algo, size)] = median(load(f)["frame_ms"])
            sizes.add(size)
            algos.add(algo)
    sizes = sorted(sizes, key=size_key)
    algos = sorted(algos, key=lambda a: (a != "pt", a))
    lines = ["| scene | size | " + " | ".join(f"{a} ms | {a} fps" for a in algos)
             + f" | {STUDY}: its scene, pt ms, bdpt ms |"]
    lines.append("| --- | --- | " + " | ".join("--- | ---" for _ in algos) + " | --- |")
    for size in sizes:
        for scene in scenes:
            cells = []
            for a in algos:
                ms = rows.get((scene, a, size))
                cells.append("- | -" if ms is None else f"{ms:.2f} | {1000.0 / ms:.0f}")
            study = STUDY_FRAME_MS.get((scene, size))
            cells.append("-" if study is None else f"{STUDY_SCENES[scene]}: {study[0]}, {study[1]}")
            lines.append(f"| {scene} | {size} | " + " | ".join(cells) + " |")
    return lines


def denoiser_table(out):
    times = {}
    for f in sorted(out.glob("denoise_*_*.json")):
        _, denoiser, size = f.stem.split("_", 2)
        passes = load(f)["passes_ms"]
        prefix = "svgf." if denoiser == "svgf" else f"{denoiser}."
        times[(denoiser, size)] = sum(median(v) for k, v in passes.items() if k.startswith(prefix))
    sizes = sorted({s for _, s in times}, key=size_key)
    denoisers = sorted({d for d, _ in times})
    lines = ["| denoiser | " + " | ".join(sizes) + " |", "| --- |" + " --- |" * len(sizes)]
    for d in denoisers:
        lines.append(f"| {d} | " + " | ".join(f"{times[(d, s)]:.2f} ms" if (d, s) in times else "-" for s in sizes) + " |")
    lines.append(f"| OptiX, {STUDY} | "
                 + " | ".join(f"{STUDY_DENOISER_MS[s]} ms" if s in STUDY_DENOISER_MS else "-" for s in sizes) + " |")
    return lines


def at_time(config, ms):
    """The row measured for `ms` of GPU time where `ms` is on converge's time ladder (the first frame
    to reach it), else the last measured row at or before it; None when the configuration did not
    run that long."""
    if config["gpu_ms"] < ms:
        return None
    for r in config["rows"]:
        if r.get("target_ms") == ms:
            return r
    best = None
    for r in config["rows"]:
        if r["gpu_ms"] <= ms * 1.0001:
            best = r
    return best


def quality_table(summary):
    lines = ["| configuration | " + " | ".join(f"DSSIM at {t / 1000:g} s" for t in CHECKPOINTS_MS) + " | frames at the end |"]
    lines.append("| --- |" + " --- |" * (len(CHECKPOINTS_MS) + 1))
    for c in summary["configurations"]:
        cells = []
        for t in CHECKPOINTS_MS:
            r = at_time(c, t)
            cells.append("-" if r is None else f"{r['dssim']:.4f} ({r['frame']})")
        lines.append(f"| {c['config']} | " + " | ".join(cells) + f" | {c['frames']} |")
    if summary["scene"] == "classroom":
        for config, points in STUDY_CLASSROOM_DSSIM.items():
            cells = [f"{d:.4f} ({n} spp" + (f", at {t:g} s)" if t * 1000 not in CHECKPOINTS_MS else ")")
                     for d, n, t in points]
            lines.append(f"| {STUDY}: {config} | " + " | ".join(cells) + " | - |")
    return lines


def converge_table(summary):
    targets = summary["targets"]
    names = list(targets)
    lines = [
        "| configuration | ms per frame | final DSSIM | final FLIP | final relMSE | "
        + " | ".join(f"GPU ms to {k} < {targets[k]}" for k in names)
        + " |",
        "| --- |" + " --- |" * (4 + len(names)),
    ]
    for c in summary["configurations"]:
        f = c["final"]
        reach = c.get("time_to_converge_ms") or {}
        cells = [("-" if reach.get(k) is None else f"{reach[k]:.0f}") for k in names]
        star = " (Pareto)" if any(c.get("pareto", {}).values()) else ""
        lines.append(
            f"| {c['config']}{star} | {c['gpu_ms_per_frame']:.2f} | {f['dssim']:.4f} | {f['flip']:.4f} | "
            f"{f['rel_mse']:.4f} | " + " | ".join(cells) + " |"
        )
    return lines


def stability_table(out):
    """Per method of the camera-path sequence: median GPU ms per frame and the mean metrics."""
    folder = out / "stability"
    means = {}
    for line in (folder / "metrics.csv").read_text().splitlines()[1:]:
        row = line.split(",")
        if row[1] == "mean":
            means[row[0]] = row
    header = (folder / "metrics.csv").read_text().splitlines()[0].split(",")
    col = {name: header.index(name) for name in ("rel_mse", "flip", "temporal_instability")}
    lines = ["| method | GPU ms per frame | temporal instability | relMSE | FLIP |",
             "| --- | --- | --- | --- | --- |"]
    for method, row in means.items():
        times_file = folder / method / "gpu_ms.txt"
        ms = "-"
        if times_file.exists():
            times = sorted(float(t) for t in times_file.read_text().split())
            ms = f"{times[len(times) // 2]:.2f}"
        lines.append(f"| {method} | {ms} | {float(row[col['temporal_instability']]):.4f} | "
                     f"{float(row[col['rel_mse']]):.4f} | {float(row[col['flip']]):.4f} |")
    return lines


def time_to_error(config, metric, error):
    """The GPU time at which the configuration's `metric` first falls to `error`, interpolated
    log-log between the measured times around it (errors fall about as a power of the time); None
    when it never does within its run."""
    before = None
    for row in config["rows"]:
        if row[metric] <= error:
            if before is None or min(before[metric], row[metric], error) <= 0:
                return row["gpu_ms"]
            (t0, e0), (t1, e1) = (before["gpu_ms"], before[metric]), (row["gpu_ms"], row[metric])
            f = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
        before = row
    return None


def mitsuba_table(summary):
    """Per image of Mitsuba's series: its time and relMSE beside the GPU time each of Lucid's
    configurations took to the same relMSE (measured at converge's time ladder, interpolated
    between its steps), times as each measured them."""
    mitsuba = summary["external"][0]
    configs = summary["configurations"]
    lines = [
        "| spp | Mitsuba ms | Mitsuba relMSE | "
        + " | ".join(f"Lucid {c['config']} ms to that relMSE (x faster)" for c in configs) + " |",
        "| --- |" + " --- |" * (2 + len(configs)),
    ]
    for p in mitsuba["points"]:
        times = []
        for c in configs:
            ms = time_to_error(c, "rel_mse", p["rel_mse"])
            times.append("-" if ms is None else f"{ms:.1f} ({p['ms'] / ms:.2f}x)")
        lines.append(f"| {p['spp']} | {p['ms']:.1f} | {p['rel_mse']:.5f} | " + " | ".join(times) + " |")
    return lines


def main():
    out = Path(sys.argv[1])
    scenes = sorted(p.parent.name for p in out.glob("*/converge.json") if p.parent.name != "mitsuba")
    device = "unknown"
    for f in out.glob("*/bench_*.json"):
        device = load(f)["device"]
        break
    driver = (out / "device.txt").read_text().strip() if (out / "device.txt").exists() else device
    print("# Lucid: speed against accuracy\n")
    print(f"Measured on {driver}. Every command is in `commands.txt`; `generate.sh` ran them all.\n")
    print("## Frame time per scene and algorithm (the study's Table 4.1)\n")
    print("One sample per pixel a frame, path depth 8, no denoiser; medians over the frames.\n")
    print("\n".join(frame_table(out, scenes)) + "\n")
    print("## Denoiser time per image size (the study's Table 4.2)\n")
    print("The sum of the denoiser's passes (medians) on `classroom` (else the first scene), path "
          "tracing, 1 sample per pixel.\n")
    print("\n".join(denoiser_table(out)) + "\n")
    if (out / "stability" / "metrics.csv").exists():
        print("## Stability against time per frame (camera path)\n")
        print("The scene's camera path (`lucid sequence`, 1 sample per pixel a frame): each "
              "method's median GPU time per frame (the whole frame: G-buffer, light transport, "
              "denoiser, tone mapping) and its means over the path against the reference.\n")
        print("\n".join(stability_table(out)) + "\n")
        print("![stability against GPU time per frame](stability/stability.svg)\n")
    if (out / "mitsuba" / "converge.json").exists():
        summary = load(out / "mitsuba" / "converge.json")
        mitsuba = summary["external"][0]
        series = load(out / "mitsuba" / "series.json")
        print("## Lucid against Mitsuba 3 (Cornell box)\n")
        print(f"Mitsuba's `cornell_box()` and Lucid's transcription (`cornell-box`), "
              f"{summary['size'][0]}x{summary['size'][1]}, path depth {summary['max_depth']}, no "
              f"denoiser, both measured by `lucid converge` against the same reference "
              f"(Mitsuba at {series['reference']['spp']} samples per pixel, other seeds). "
              f"{mitsuba['renderer']} on {mitsuba['device']}: wall time of "
              f"each image (render calls of at most 64 samples per pixel, median of 3, after a "
              f"warm-up at that count). Lucid: the GPU time of its frames' passes (path tracing, "
              f"accumulation, tone mapping), summed as samples accumulate, at 1 and 16 samples "
              f"per pixel a frame; the time it took to each Mitsuba image's relMSE is interpolated "
              f"between the times converge measured it at.\n")
        print("\n".join(mitsuba_table(summary)) + "\n")
        print("![relMSE against time](mitsuba/error_vs_time_rel_mse.svg) "
              "![FLIP against time](mitsuba/error_vs_time_flip.svg)\n")
    for scene in scenes:
        summary = load(out / scene / "converge.json")
        print(f"## {scene}\n")
        print(
            f"Still camera, {summary['size'][0]}x{summary['size'][1]}, reference "
            f"{summary['reference_spp']} samples, each configuration (algorithm/denoiser/samples "
            f"per pixel per frame) for {summary['budget_ms']:g} ms of GPU time, each measured at "
            f"the first frame to reach each of the same GPU times"
            + (f" ({', '.join(f'{t:g}' for t in summary['time_ladder_ms'])} ms)"
               if "time_ladder_ms" in summary else "") + ".\n"
        )
        print("DSSIM (1/SSIM - 1) after the study's accumulated GPU times (the last measurement at "
              "or before each, or the one for it where it is one of the measured times), frames in "
              "brackets (the study's Table 4.3):\n")
        print("\n".join(quality_table(summary)) + "\n")
        print("\n".join(converge_table(summary)) + "\n")
        print(f"![speed against accuracy]({scene}/speed_vs_accuracy.svg) "
              f"![DSSIM against GPU time]({scene}/error_vs_time_dssim.svg) "
              f"![time to converge]({scene}/time_to_converge.svg)\n")


if __name__ == "__main__":
    main()
