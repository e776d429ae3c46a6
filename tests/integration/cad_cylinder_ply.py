# quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
"""A closed cylinder as CAD tessellations write one, as cad_cylinder(around, 1, height) in
tests/fixtures/shapes.cpp makes it: a row of long triangles round its side, each cap a fan
round a vertex at its centre. Plain Python, for meshlabserver's test and pymeshlab's.

Usage: cad_cylinder_ply.py OUT.ply [AROUND]
"""
import math
import sys

from ascii_ply import write_ply


def mesh(around=64, height=2.0):
    """The cylinder's points and triangles, in the fixture's order: the side's triangles,
    then the caps' fans, bottom and top in turn."""
    ring = [(math.cos(2 * math.pi * k / around), math.sin(2 * math.pi * k / around)) for k in range(around)]
    points = [(x, y, z) for z in (0.0, height) for x, y in ring] + [(0.0, 0.0, 0.0), (0.0, 0.0, height)]
    bottom, top = 2 * around, 2 * around + 1
    ks = [(k, (k + 1) % around) for k in range(around)]
    faces = [f for k, k1 in ks for f in ((k, k1, k1 + around), (k, k1 + around, k + around))]
    faces += [f for k, k1 in ks for f in ((bottom, k1, k), (top, k + around, k1 + around))]
    return points, faces


def write(path, around=64, height=2.0):
    return write_ply(path, *mesh(around, height))


if __name__ == "__main__":
    write(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 64)
