#!/usr/bin/env python3
"""Writes the fuzzers' seed corpus: small meshes in every format the readers take, and
small images in every format read_image() takes.

Each mesh file starts with the byte that picks its format (fuzz_input.h: PLY, OBJ, OFF or
STL by its low two bits); the simplify fuzzer's seeds have a second byte, and both bytes
pick its mode, target and options (simplify_fuzzer.cpp), so the seeds vary them. Images
have no header byte: the reader tells their format by their first bytes.
Usage: make_seeds.py FOLDER (it writes FOLDER/read_mesh_fuzzer/FORMAT, a folder per format,
FOLDER/simplify_fuzzer and FOLDER/read_image_fuzzer)
"""
import math
import os
import struct
import sys
import zlib

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


def uv(v):
    """Texture coordinates by planar projection onto x and y, within [0, 1]."""
    lo = [min(p[k] for p in v) for k in range(2)]
    span = [max(max(p[k] for p in v) - lo[k], 1e-9) for k in range(2)]
    return [tuple((p[k] - lo[k]) / span[k] for k in range(2)) for p in v]


def obj_textured(v, f):
    """Its materials in its own lines (fuzz_input.h writes the file as m.mtl too): the
    first half of the faces textured with t.png, the rest coloured."""
    head = "mtllib m.mtl\nnewmtl a\nKd 1 0.5 0\nmap_Kd t.png\nnewmtl b\nKd 0 0 1\nd 0.5\n"
    rows = "".join(f"v {x} {y} {z}\n" for x, y, z in v) + "".join(f"vt {s} {t}\n" for s, t in uv(v))
    faces = [("usemtl a\n" if i == 0 else "usemtl b\n" if i == len(f) // 2 else "") +
             "f " + " ".join(f"{j + 1}/{j + 1}" for j in p) + "\n" for i, p in enumerate(f)]
    return head + rows + "".join(faces)


def ply_textured(v, f):
    """As MeshLab writes a textured mesh: the image in a comment, coordinates per face corner."""
    t = uv(v)
    head = ["ply", "format ascii 1.0", "comment TextureFile t.png", f"element vertex {len(v)}", "property float x",
            "property float y", "property float z", f"element face {len(f)}",
            "property list uchar int vertex_indices", "property list uchar float texcoord", "end_header"]
    faces = [f"{len(p)} " + " ".join(map(str, p)) + f" {2 * len(p)} " + " ".join(f"{t[j][0]} {t[j][1]}" for j in p)
             for p in f]
    return "\n".join(head + [" ".join(map(str, p)) for p in v] + faces) + "\n"


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


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png(w, h, depth, colour, rows, chunks=b"", interlace=0):
    ihdr = struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, interlace)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + chunks + png_chunk(b"IDAT", zlib.compress(rows)) +
            png_chunk(b"IEND", b""))


def jpeg_grey():
    """An 8 x 8 grey baseline JPEG: one block, its DC difference 0 and its ACs an end of
    block, each coded by a one-bit Huffman code."""
    def segment(marker, body):
        return bytes([0xFF, marker]) + struct.pack(">H", len(body) + 2) + body
    one_code = lambda symbol: bytes([1] + [0] * 15 + [symbol])
    return (b"\xff\xd8" + segment(0xDB, b"\0" + bytes([1] * 64)) +
            segment(0xC0, struct.pack(">BHHB", 8, 8, 8, 1) + b"\x01\x11\x00") +
            segment(0xC4, b"\x00" + one_code(0) + b"\x10" + one_code(0)) +
            segment(0xDA, b"\x01\x01\x00\x00\x3f\x00") + b"\x3f\xff\xd9")


def images(w=4, h=3):
    """A small image in each format and layout read_image() takes, by file name."""
    texel = lambda x, y: (x * 60, y * 80, 128)
    rgb = bytes(c for y in range(h) for x in range(w) for c in texel(x, y))
    bgr_up = [bytes(c for x in range(w) for c in reversed(texel(x, y))) for y in reversed(range(h))]  # BMP, TGA
    rgba = lambda xs, ys: b"".join(b"\0" + bytes(c for x in xs for c in texel(x, y) + (255 - x,)) for y in ys)
    rgba_rows = rgba(range(w), range(h))
    # Adam7's seven passes, each a smaller image of every dx-th texel from x0 (rows alike).
    adam7 = b"".join(rgba(range(x0, w, dx), range(y0, h, dy)) for x0, y0, dx, dy in (
        (0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2))
        if x0 < w and y0 < h)
    grey16_rows = b"".join(b"\0" + b"".join(struct.pack(">H", x * 9000 + y * 300) for x in range(w)) for y in range(h))
    palette_rows = b"".join(b"\0" + bytes((x + y) % 3 for x in range(w)) for y in range(h))
    palette = png_chunk(b"PLTE", bytes([255, 0, 0, 0, 255, 0, 0, 0, 255])) + png_chunk(b"tRNS", b"\x80")
    bmp_rows = b"".join(r.ljust((w * 3 + 3) // 4 * 4, b"\0") for r in bgr_up)
    bmp = b"BM" + struct.pack("<IHHI", 54 + len(bmp_rows), 0, 0, 54) + struct.pack(
        "<IiiHHIIiiII", 40, w, h, 1, 24, 0, len(bmp_rows), 2835, 2835, 0, 0) + bmp_rows
    tga = lambda kind, depth, descriptor: struct.pack("<BBBHHBHHHHBB", 0, 0, kind, 0, 0, 0, 0, 0, w, h, depth,
                                                      descriptor)
    rle = b"".join(bytes((0x80 | (w - 1),) + tuple(reversed(texel(0, y))) + (255,)) for y in reversed(range(h)))
    decimal = lambda samples: b" ".join(b"%d" % v for v in samples) + b"\n"
    rows = [[(x + y) % 2 for x in range(w)] for y in range(h)]  # a bitmap's checkerboard (w <= 8)
    bits = [b for r in rows for b in r]
    return {"rgba.png": png(w, h, 8, 6, rgba_rows), "grey16.png": png(w, h, 16, 0, grey16_rows),
            "palette.png": png(w, h, 8, 3, palette_rows, palette),
            "interlaced.png": png(w, h, 8, 6, adam7, interlace=1), "grey.jpg": jpeg_grey(), "rgb.bmp": bmp,
            "rgb.tga": tga(2, 24, 0) + b"".join(bgr_up), "rle.tga": tga(10, 32, 8) + rle,
            "rgb.ppm": b"P6 %d %d 255\n" % (w, h) + rgb, "grey.pgm": b"P5\n%d %d\n255\n" % (w, h) + rgb[:w * h],
            "plain.ppm": b"P3 %d %d 255\n" % (w, h) + decimal(rgb), "plain.pgm": b"P2 %d %d 255\n" % (w, h) +
            decimal(rgb[:w * h]), "plain.pbm": b"P1 %d %d\n" % (w, h) + decimal(bits),
            "bits.pbm": b"P4 %d %d\n" % (w, h) + bytes(int("".join(map(str, r)).ljust(8, "0"), 2) for r in rows)}


def main(folder):
    for sub in [f"read_mesh_fuzzer/{ext}" for ext in EXTENSIONS] + ["simplify_fuzzer"]:
        os.makedirs(os.path.join(folder, sub), exist_ok=True)
    shapes = {"sphere": sphere(8, 10), "grid": grid(), "cube": cube()}
    n = 0
    for name, (v, f) in shapes.items():
        files = [(PLY, ply_ascii(v, f), ""), (PLY, ply_ascii(v, f, colours=True), ""), (PLY, ply_binary(v, f), ""),
                 (OBJ, obj(v, f), ""), (OFF, off(v, f), ""), (STL, stl_ascii(v, f), ""), (STL, stl_binary(v, f), ""),
                 (OBJ, obj_textured(v, f), "_textured"), (PLY, ply_textured(v, f), "_textured")]
        for fmt, body, kind in files:
            data = body if isinstance(body, bytes) else body.encode()
            seed = f"{name}_{n:03d}{kind}"
            with open(os.path.join(folder, "read_mesh_fuzzer", EXTENSIONS[fmt], seed), "wb") as out:
                out.write(bytes([fmt]) + data)
            # The simplify fuzzer's mode byte: uniform to a quarter, adaptive to half, adaptive
            # with automatic halting; its options byte: none, a kept border with creases, fast
            # with square quads and a tight tolerance.
            for mode, options in ((0x40, 0x00), (0x84, 0x05), (0x0C, 0xA8)):
                with open(os.path.join(folder, "simplify_fuzzer", f"{seed}_{mode:02x}"), "wb") as out:
                    out.write(bytes([fmt | mode, options]) + data)
            n += 1
    os.makedirs(os.path.join(folder, "read_image_fuzzer"), exist_ok=True)
    seeds = images()
    for name, data in seeds.items():
        with open(os.path.join(folder, "read_image_fuzzer", name), "wb") as out:
            out.write(data)
    print(f"{n} meshes in {folder}/read_mesh_fuzzer/FORMAT and, with options, in {folder}/simplify_fuzzer; "
          f"{len(seeds)} images in {folder}/read_image_fuzzer")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
