#!/usr/bin/env python3
"""Writes a triangulated torus as an ASCII PLY: a small generated mesh for tests.

    python3 datasets/make_torus.py OUT.ply [rings segments]
"""
import math
import sys


def main():
    out = sys.argv[1]
    rings = int(sys.argv[2]) if len(sys.argv) > 2 else 96
    segs = int(sys.argv[3]) if len(sys.argv) > 3 else 48
    R, r = 1.0, 0.35
    vertices, faces = [], []
    for i in range(rings):
        u = 2 * math.pi * i / rings
        for j in range(segs):
            v = 2 * math.pi * j / segs
            vertices.append(((R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u),
                             r * math.sin(v)))

    def vid(i, j):
        return (i % rings) * segs + (j % segs)

    for i in range(rings):
        for j in range(segs):
            faces.append((vid(i, j), vid(i + 1, j), vid(i + 1, j + 1)))
            faces.append((vid(i, j), vid(i + 1, j + 1), vid(i, j + 1)))
    with open(out, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                % (len(vertices), len(faces)))
        for p in vertices:
            f.write("%.7f %.7f %.7f\n" % p)
        for t in faces:
            f.write("3 %d %d %d\n" % t)


if __name__ == "__main__":
    main()
