#!/usr/bin/env python3
"""Writes a real terrain as a binary PLY triangle mesh, in metres: an open height field
scan, for want of the paper's Rampart (bench/RESULTS.md, "An open scan").

The elevations are matplotlib's sample DEM `jacksboro_fault_dem.npz` (USGS, 3 arc-seconds,
344 x 403 posts, whole metres), read from matplotlib's wheel on PyPI; no third-party file
is committed here. Needs numpy (the project's .venv has it):

    .venv/bin/python datasets/make_terrain.py OUT.ply [--step 2] [--exaggeration 1] [--npz PATH]

Without --npz the wheel is fetched with `pip download matplotlib --no-deps`.
"""
import argparse
import io
import pathlib
import subprocess
import sys
import tempfile
import zipfile

import numpy as np

NPZ_IN_WHEEL = "matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz"


def fetch_npz():
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([sys.executable, "-m", "pip", "download", "matplotlib", "--no-deps", "-q", "-d", tmp],
                       check=True)
        wheel = next(pathlib.Path(tmp).glob("matplotlib-*.whl"))
        with zipfile.ZipFile(wheel) as w:
            return w.read(NPZ_IN_WHEEL)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--step", type=int, default=2, help="keep every STEP-th post each way (2: 68,742 triangles)")
    ap.add_argument("--exaggeration", type=float, default=1.0, help="vertical scale (1: true scale)")
    ap.add_argument("--npz", help="jacksboro_fault_dem.npz, if already at hand")
    a = ap.parse_args()
    dem = np.load(io.BytesIO(pathlib.Path(a.npz).read_bytes() if a.npz else fetch_npz()))
    z = dem["elevation"].astype(np.float64)[::a.step, ::a.step]
    ny, nx = z.shape
    # Degrees to metres at the DEM's mean latitude: a few metres of error over its 30 km
    # would not matter; the shape is what is measured.
    lat = np.radians(0.5 * (float(dem["ymin"]) + float(dem["ymax"])))
    dx = float(dem["dx"]) * a.step * 111320.0 * np.cos(lat)
    dy = float(dem["dy"]) * a.step * 110574.0
    x, y = np.meshgrid(np.arange(nx) * dx, np.arange(ny) * dy)
    points = np.stack([x.ravel(), y.ravel(), a.exaggeration * z.ravel()], axis=1).astype("<f4")
    # Two triangles per cell, corners v, v+1, v+nx+1, v+nx counter-clockwise.
    v = (np.arange(ny - 1)[:, None] * nx + np.arange(nx - 1)[None, :]).ravel()
    cells = np.stack([np.stack([v, v + 1, v + nx + 1], axis=1), np.stack([v, v + nx + 1, v + nx], axis=1)], axis=1)
    faces = np.zeros(2 * len(v), dtype=[("n", "u1"), ("corners", "<i4", 3)])
    faces["n"] = 3
    faces["corners"] = cells.reshape(-1, 3)
    with open(a.out, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                 "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(points), len(faces))).encode())
        f.write(points.tobytes())
        f.write(faces.tobytes())
    print("%s: %d vertices, %d triangles, posts %.1f x %.1f m" % (a.out, len(points), len(faces), dx, dy))


if __name__ == "__main__":
    main()
