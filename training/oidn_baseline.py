"""Intel Open Image Denoise per frame, the baseline the learned denoiser is measured against: reads a
`lucid sequence` folder's noisy 1-sample frames (`none/`) with their first-hit `albedo/` and
`normal/` images, writes `oidn/NNNN.exr`; `lucid evaluate DIR` then scores it beside the others.

    python3 oidn_baseline.py DIR [--device cuda|cpu]

Needs `pyoidn` (with `cffi`) and `OpenEXR`; on `cuda`, PyTorch (the images go to the GPU as
tensors, on the stream OIDN's CUDA device is bound to).
"""

import argparse
from pathlib import Path

import numpy as np
import OpenEXR
import pyoidn
import torch


def read(path):
    """The RGB channels of an EXR image that Lucid wrote (one interleaved RGBA channel set)."""
    with OpenEXR.File(str(path)) as f:
        rgba = f.channels()["RGBA"].pixels
    return np.ascontiguousarray(rgba[:, :, :3].astype(np.float32))


def write(path, rgb):
    h, w, _ = rgb.shape
    rgba = np.concatenate([rgb, np.ones((h, w, 1), np.float32)], axis=2)
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    with OpenEXR.File(header, {"RGBA": rgba}) as f:
        f.write(str(path))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--device", choices=["cuda", "cpu"], default="cuda")
    args = ap.parse_args()
    root = Path(args.dir)
    out = root / "oidn"
    out.mkdir(exist_ok=True)
    device = pyoidn.Device.from_torch(args.device)
    device.commit()
    frames = sorted((root / "none").glob("*.exr"))
    if not frames:
        raise SystemExit(f"no frames in {root / 'none'}")
    for frame in frames:
        images = [read(frame), read(root / "albedo" / frame.name), read(root / "normal" / frame.name)]
        color, albedo, normal = (torch.from_numpy(i).to(args.device).contiguous() for i in images)
        result = torch.zeros_like(color)
        filt = pyoidn.Filter(device, "RT")
        filt.set_image(pyoidn.OIDN_IMAGE_COLOR, color, pyoidn.OIDN_FORMAT_FLOAT3)
        filt.set_image(pyoidn.OIDN_IMAGE_ALBEDO, albedo, pyoidn.OIDN_FORMAT_FLOAT3)
        filt.set_image(pyoidn.OIDN_IMAGE_NORMAL, normal, pyoidn.OIDN_FORMAT_FLOAT3)
        filt.set_image(pyoidn.OIDN_IMAGE_OUTPUT, result, pyoidn.OIDN_FORMAT_FLOAT3)
        filt.set_bool("hdr", True)
        filt.commit()
        filt.execute()
        device.wait()
        filt.release()
        write(out / frame.name, result.cpu().numpy())
    device.release()
    print(f"{len(frames)} frames -> {out}")


if __name__ == "__main__":
    main()
