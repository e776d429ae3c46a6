# quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
"""A CAD-like test input: the unit cube, n x n cells a side, each split in two, as ASCII PLY, the way
tri_cube() in tests/fixtures/shapes.cpp makes it. Plain Python, for meshlabserver's test and pymeshlab's.

Usage: cube_ply.py OUT.ply [N]
"""
import struct
import sys

from ascii_ply import write_ply


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
    return write_ply(path, pos, faces)


if __name__ == "__main__":
    write(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 12)
