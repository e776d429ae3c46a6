#!/usr/bin/env python3
"""Writes the fuzzers' seed corpus: small meshes in every format the readers take.

Each file starts with the byte that picks its format (fuzz_input.h: PLY, OBJ, OFF or STL
by its low two bits); the simplify fuzzer's seeds have a second byte, and both bytes pick
its mode, target and options (simplify_fuzzer.cpp), so the seeds vary them.
Usage: make_seeds.py FOLDER (it writes FOLDER/read_mesh_fuzzer/FORMAT, a folder per format,
and FOLDER/simplify_fuzzer)
"""
import math
import os
import struct
import sys

PLY, OBJ, OFF, STL = range(4)
EXTENSIONS = ("ply", "obj", "off", "stl")


def sphere(rings=4, segments=6):
    v = [(0.0, 0.0, 1.0)]
    for i in range(1, rings):
        t = math.pi * i / rings
        v += [(math.sin(t) * math.cos(2 * math.pi * j / segments),
               math.sin(t) * math.sin(2 * math.pi * j / segments), math.cos(t)) for j in range(segments)]
    v.append((0.0, 0.0, -1.0))
    ring = lambda i, j: 1 + (i - 1) * segments + j % segments
    f = [(0, ring(1, j), ring(1, j + 1)) for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            f += [(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)), (ring(i, j), ring(i + 1, j + 1), ring(i, j + 1))]
    f += [(len(v) - 1, ring(rings - 1, j + 1), ring(rings - 1, j)) for j in range(segments)]
    return v, f


def grid(n=3):
    v = [(float(x), float(y), 0.1 * ((x * y) % 3)) for y in range(n + 1) for x in range(n + 1)]
    f = [(y * (n + 1) + x, y * (n + 1) + x + 1, (y + 1) * (n + 1) + x + 1, (y + 1) * (n + 1) + x)
         for y in range(n) for x in range(n)]
    return v, f


def cube():
    v = [(x, y, z) for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)]
    f = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return v, f


def triangles(f):
    return [t for p in f for t in ([p] if len(p) == 3 else [(p[0], p[1], p[2]), (p[0], p[2], p[3])])]


def ply_ascii(v, f, colours=False):
    head = ["ply", "format ascii 1.0", f"element vertex {len(v)}", "property float x", "property float y",
            "property float z"]
    head += ["property uchar red", "property uchar green", "property uchar blue"] if colours else []
    head += [f"element face {len(f)}", "property list uchar int vertex_indices", "end_header"]
    rows = [" ".join(map(str, p)) + (f" {i * 40 % 256} 128 {255 - i * 9 % 256}" if colours else "")
            for i, p in enumerate(v)]
    return "\n".join(head + rows + [f"{len(p)} " + " ".join(map(str, p)) for p in f]) + "\n"


def ply_binary(v, f):
    head = ("ply\nformat binary_little_endian 1.0\ncomment seed\n"
            f"element vertex {len(v)}\nproperty float x\nproperty float y\nproperty float z\n"
            f"element face {len(f)}\nproperty list uchar int vertex_indices\nproperty uchar flags\nend_header\n")
    body = b"".join(struct.pack("<3f", *p) for p in v)
    body += b"".join(struct.pack(f"<B{len(p)}iB", len(p), *p, 0) for p in f)
    return head.encode() + body


def obj(v, f):
    return "".join(f"v {x} {y} {z}\n" for x, y, z in v) + "vn 0 0 1\n" + "".join(
        "f " + " ".join(f"{i + 1}//1" for i in p) + "\n" for p in f)


def off(v, f):
    return f"OFF\n{len(v)} {len(f)} 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in v) + "".join(
        f"{len(p)} " + " ".join(map(str, p)) + "\n" for p in f)


def stl_ascii(v, f):
    out = "solid seed\n"
    for t in triangles(f):
        out += "facet normal 0 0 0\nouter loop\n" + "".join(
            "vertex {} {} {}\n".format(*v[i]) for i in t) + "endloop\nendfacet\n"
    return out + "endsolid seed\n"


def stl_binary(v, f):
    tris = triangles(f)
    return b"seed".ljust(80, b" ") + struct.pack("<I", len(tris)) + b"".join(
        struct.pack("<12fH", 0, 0, 0, *v[t[0]], *v[t[1]], *v[t[2]], 0) for t in tris)


def main(folder):
    for sub in [f"read_mesh_fuzzer/{ext}" for ext in EXTENSIONS] + ["simplify_fuzzer"]:
        os.makedirs(os.path.join(folder, sub), exist_ok=True)
    shapes = {"sphere": sphere(8, 10), "grid": grid(), "cube": cube()}
    n = 0
    for name, (v, f) in shapes.items():
        files = [(PLY, ply_ascii(v, f)), (PLY, ply_ascii(v, f, colours=True)), (PLY, ply_binary(v, f)),
                 (OBJ, obj(v, f)), (OFF, off(v, f)), (STL, stl_ascii(v, f)), (STL, stl_binary(v, f))]
        for fmt, body in files:
            data = body if isinstance(body, bytes) else body.encode()
            with open(os.path.join(folder, "read_mesh_fuzzer", EXTENSIONS[fmt], f"{name}_{n:03d}"), "wb") as out:
                out.write(bytes([fmt]) + data)
            # The simplify fuzzer's mode byte: uniform to a quarter, adaptive to half, adaptive
            # with automatic halting; its options byte: none, a kept border with creases, fast
            # with square quads and a tight tolerance.
            for mode, options in ((0x40, 0x00), (0x84, 0x05), (0x0C, 0xA8)):
                with open(os.path.join(folder, "simplify_fuzzer", f"{name}_{n:03d}_{mode:02x}"), "wb") as out:
                    out.write(bytes([fmt | mode, options]) + data)
            n += 1
    print(f"{n} meshes in {folder}/read_mesh_fuzzer/FORMAT and, with options, in {folder}/simplify_fuzzer")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
