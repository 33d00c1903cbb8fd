"""Writes a glTF binary (.glb) of one mesh with about N triangles: a gently rippled grid (under a
light and a camera), for checking what a scene of tens of millions of triangles costs, or that it
is refused with a clear error where it does not fit (`bench/README.md`, "A 50 M triangle scene").

    python3 bench/big_scene.py --triangles 50000000 --out /tmp/big.glb

Needs numpy. Positions and normals float32, indices uint32 (the glTF JSON is a few hundred bytes;
the file is about 40 bytes a triangle).
"""

import argparse
import json
import struct

import numpy as np


def grid(triangles):
    """Vertices, normals and triangle indices of an n x n grid of quads with >= `triangles`."""
    n = int(np.ceil(np.sqrt(triangles / 2)))
    u = np.linspace(-1.0, 1.0, n + 1, dtype=np.float32)
    x, z = np.meshgrid(u, u)
    y = 0.02 * np.sin(40.0 * x) * np.cos(40.0 * z)
    positions = np.stack([x, y, z], -1).reshape(-1, 3).astype(np.float32)
    # Normal of the height field y(x, z): (-dy/dx, 1, -dy/dz), normalized.
    dx = 0.8 * np.cos(40.0 * x) * np.cos(40.0 * z)
    dz = -0.8 * np.sin(40.0 * x) * np.sin(40.0 * z)
    normals = np.stack([-dx, np.ones_like(dx), -dz], -1).reshape(-1, 3)
    normals = (normals / np.linalg.norm(normals, axis=1, keepdims=True)).astype(np.float32)
    row = np.arange(n, dtype=np.uint32)
    a = (row[None, :] + (n + 1) * row[:, None]).reshape(-1)
    b, c, d = a + 1, a + n + 2, a + n + 1
    indices = np.stack([a, c, b, a, d, c], -1).reshape(-1).astype(np.uint32)
    return positions, normals, indices


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--triangles", type=int, required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    positions, normals, indices = grid(args.triangles)
    blobs = [positions.tobytes(), normals.tobytes(), indices.tobytes()]
    offsets = np.cumsum([0] + [len(b) for b in blobs])
    views = [{"buffer": 0, "byteOffset": int(offsets[i]), "byteLength": len(b)} for i, b in enumerate(blobs)]
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"mesh": 0},
            {"camera": 0, "translation": [0.0, 1.2, 2.2], "rotation": [-0.2588, 0.0, 0.0, 0.9659]},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0.0, 2.0, 0.0]},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.01}}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 2000.0}]}},
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": positions.min(0).tolist(), "max": positions.max(0).tolist()},
            {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
        ],
        "bufferViews": views,
        "buffers": [{"byteLength": int(offsets[-1])}],
    }
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    total = 12 + 8 + len(js) + 8 + int(offsets[-1])
    with open(args.out, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, total))
        f.write(struct.pack("<II", len(js), 0x4E4F534A))
        f.write(js)
        f.write(struct.pack("<II", int(offsets[-1]), 0x004E4942))
        for b in blobs:
            f.write(b)
    print(f"{args.out}: {len(indices) // 3} triangles, {len(positions)} vertices, {total / 2**20:.0f} MiB")


if __name__ == "__main__":
    main()
