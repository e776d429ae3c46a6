# quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
"""A CAD-like test input: the unit cube, n x n cells a side, each split in two, as ASCII PLY, the way
tri_cube() in tests/fixtures/shapes.cpp makes it. Plain Python, for meshlabserver's test and pymeshlab's.

Usage: cube_ply.py OUT.ply [N]
"""
import struct
import sys


def write(path, n=12):
    pos, faces, index = [], [], {}

    def vid(p):
        if p not in index:
            index[p] = len(pos)
            pos.append(p)
        return index[p]

    for axis in range(3):
        for side in (0, 1):
            u, v = (axis + 1) % 3, (axis + 2) % 3

            def at(a, b):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = float(side), a / n, b / n
                # Rounded to float, as the file's type says: MeshLab reads it so, and so do we.
                return vid(tuple(struct.unpack("3f", struct.pack("3f", *p))))

            for j in range(n):
                for i in range(n):
                    a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
                    faces += [(a, b, c), (a, c, d)] if side else [(a, c, b), (a, d, c)]
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(pos)}\nproperty float x\nproperty float y\n"
                f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        f.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in pos)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)
    return str(path)


if __name__ == "__main__":
    write(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 12)
