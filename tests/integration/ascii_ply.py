# quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
"""Writes test inputs as ASCII PLY (float coordinates, triangles), for the generators beside it."""


def write_ply(path, points, faces):
    with open(path, "w") as out:
        out.write(f"ply\nformat ascii 1.0\nelement vertex {len(points)}\nproperty float x\nproperty float y\n"
                  f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        out.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in points)
        out.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)
    return str(path)
