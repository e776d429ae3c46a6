# quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
"""A textured test input: a sphere mapped by longitude and height (a seam where the longitude wraps), whose
texture's red is the longitude and green the height (a PPM image, which MeshLab and quadsimp read), as OBJ,
material file and image. Plain Python, for meshlabserver's test and pymeshlab's.

Usage: textured_sphere.py FOLDER [ply]   (writes FOLDER/lonlat.obj, lonlat.mtl, lonlat.ppm; with ply, also
        lonlat.ply, its texture named as MeshLab writes it: comment TextureFile, texcoord per face corner)
"""
import math
import pathlib
import sys


def write(folder, n=48, size=256):
    folder = pathlib.Path(folder)
    rows = bytearray()
    for y in range(size):
        for x in range(size):
            rows += bytes((x, size - 1 - y, 0))
    (folder / "lonlat.ppm").write_bytes(b"P6 %d %d 255\n" % (size, size) + bytes(rows))
    (folder / "lonlat.mtl").write_text("newmtl lonlat\nKd 1 1 1\nmap_Kd lonlat.ppm\n")
    lines = ["mtllib lonlat.mtl", "usemtl lonlat"]
    around = 2 * n
    for i in range(1, n):
        theta = math.pi * i / n
        for j in range(around):
            phi = 2 * math.pi * j / around
            lines.append("v %r %r %r" % (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi),
                                         math.cos(theta)))
    top, bottom = (n - 1) * around + 1, (n - 1) * around + 2
    lines += ["v 0 0 1", "v 0 0 -1"]
    ring = lambda i, j: i * around + j % around + 1  # noqa: E731 (ring i from the top, 0-based)
    coords = []

    def face(corners, uv):
        first = len(coords) + 1
        coords.extend(uv)
        lines.append("f " + " ".join("%d/%d" % (v, first + k) for k, v in enumerate(corners)))

    for j in range(around):
        u0, u1 = j / around, (j + 1) / around
        face([top, ring(0, j), ring(0, j + 1)], [((u0 + u1) / 2, 1), (u0, 1 - 1 / n), (u1, 1 - 1 / n)])
        for i in range(n - 2):
            v0, v1 = 1 - (i + 1) / n, 1 - (i + 2) / n
            face([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)], [(u0, v0), (u0, v1), (u1, v1)])
            face([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)], [(u0, v0), (u1, v1), (u1, v0)])
        face([bottom, ring(n - 2, j + 1), ring(n - 2, j)], [((u0 + u1) / 2, 0), (u1, 1 / n), (u0, 1 / n)])
    text = "\n".join(lines[:2 + (n - 1) * around + 2]) + "\n"
    text += "".join("vt %r %r\n" % c for c in coords)
    text += "\n".join(lines[2 + (n - 1) * around + 2:]) + "\n"
    (folder / "lonlat.obj").write_text(text)
    return folder / "lonlat.obj"


def write_ply(folder):
    """The same sphere as an ASCII PLY with its texture (MeshLab's way), from write()'s OBJ."""
    folder = pathlib.Path(folder)
    obj = write(folder).read_text().split("\n")
    vertices = [line[2:] for line in obj if line.startswith("v ")]
    coords = [line[3:] for line in obj if line.startswith("vt ")]
    faces = []
    for line in obj:
        if line.startswith("f "):
            corners = [c.split("/") for c in line.split()[1:]]
            faces.append("3 %s 6 %s" % (" ".join(str(int(v) - 1) for v, _ in corners),
                                        " ".join(coords[int(t) - 1] for _, t in corners)))
    header = ["ply", "format ascii 1.0", "comment TextureFile lonlat.ppm", "element vertex %d" % len(vertices),
              "property float x", "property float y", "property float z", "element face %d" % len(faces),
              "property list uchar int vertex_indices", "property list uchar float texcoord", "end_header"]
    (folder / "lonlat.ply").write_text("\n".join(header + vertices + faces) + "\n")
    return folder / "lonlat.ply"


if __name__ == "__main__":
    print(write_ply(sys.argv[1]) if sys.argv[2:] == ["ply"] else write(sys.argv[1]))
