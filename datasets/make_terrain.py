#!/usr/bin/env python3
"""Writes a real terrain as a binary PLY triangle mesh, in metres: an open height field
scan, for want of the paper's Rampart (bench/RESULTS.md, "An open scan").

The elevations are matplotlib's sample DEM `jacksboro_fault_dem.npz` (USGS, 3 arc-seconds,
344 x 403 posts, whole metres), read from matplotlib's wheel on PyPI; no third-party file
is committed here.

    python3 datasets/make_terrain.py OUT.ply [--step 2] [--exaggeration 1] [--npz PATH]

Without --npz the wheel is fetched with `pip download matplotlib --no-deps`.
"""
import argparse
import ast
import io
import math
import pathlib
import struct
import subprocess
import sys
import tempfile
import zipfile

NPZ_IN_WHEEL = "matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz"


def read_npy(data):
    """A .npy array as (flat values, shape); only what the DEM uses (little-endian, C order)."""
    if data[:6] != b"\x93NUMPY":
        raise ValueError("not a .npy array")
    major = data[6]
    header_len = struct.unpack("<H" if major == 1 else "<I", data[8:10] if major == 1 else data[8:12])[0]
    start = 10 if major == 1 else 12
    header = ast.literal_eval(data[start:start + header_len].decode("latin1"))
    if header["fortran_order"]:
        raise ValueError("Fortran-ordered arrays are not handled")
    codes = {"<i2": "h", "<f8": "d", "<f4": "f"}
    code = codes[header["descr"]]
    shape = header["shape"]
    count = math.prod(shape) if shape else 1
    values = struct.unpack("<%d%s" % (count, code), data[start + header_len:][:count * struct.calcsize(code)])
    return values, shape


def load_dem(npz_bytes):
    with zipfile.ZipFile(io.BytesIO(npz_bytes)) as z:
        return {name[:-4]: read_npy(z.read(name)) for name in z.namelist()}


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
    dem = load_dem(pathlib.Path(a.npz).read_bytes() if a.npz else fetch_npz())
    z, (rows, cols) = dem["elevation"]
    lat = 0.5 * (dem["ymin"][0][0] + dem["ymax"][0][0])
    # Degrees to metres at the DEM's mean latitude: a few kilometres of error over its
    # 30 km would not matter; the shape is what is measured.
    dx = dem["dx"][0][0] * a.step * 111320.0 * math.cos(math.radians(lat))
    dy = dem["dy"][0][0] * a.step * 110574.0
    keep_r, keep_c = range(0, rows, a.step), range(0, cols, a.step)
    ny, nx = len(keep_r), len(keep_c)
    points = [(j * dx, i * dy, a.exaggeration * z[r * cols + c])
              for i, r in enumerate(keep_r) for j, c in enumerate(keep_c)]
    faces = []
    for i in range(ny - 1):
        for j in range(nx - 1):
            v = i * nx + j
            faces += [(v, v + 1, v + nx + 1), (v, v + nx + 1, v + nx)]
    with open(a.out, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                 "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(points), len(faces))).encode())
        f.write(b"".join(struct.pack("<3f", *p) for p in points))
        f.write(b"".join(struct.pack("<B3i", 3, *t) for t in faces))
    print("%s: %d vertices, %d triangles, posts %.1f x %.1f m" % (a.out, len(points), len(faces), dx, dy))


if __name__ == "__main__":
    main()
