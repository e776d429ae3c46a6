#!/usr/bin/env bash
# datasets/make_terrain.py on a small DEM written here in matplotlib's npz layout (no
# download): the mesh has one vertex per post, two triangles per cell, the heights in
# place, posts spaced as the degrees say, and the CLI reads and simplifies it.
# Usage: make_terrain_test.sh REPO_DIR QUADSIMP_CLI
set -euo pipefail
repo=$1 cli=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$work/dem.npz" <<'PY'
import io, struct, sys, zipfile
def npy(descr, shape, values):
    header = "{'descr': '%s', 'fortran_order': False, 'shape': %r, }" % (descr, shape)
    header += " " * (63 - (10 + len(header)) % 64) + "\n"
    code = {"<i2": "h", "<f8": "d"}[descr]
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + \
        struct.pack("<%d%s" % (len(values), code), *values)
rows, cols = 9, 11
with zipfile.ZipFile(sys.argv[1], "w") as z:
    heights = [100 + 3 * r + 2 * c for r in range(rows) for c in range(cols)]
    z.writestr("elevation.npy", npy("<i2", (rows, cols), heights))
    for name, v in (("dx", 0.001), ("dy", 0.001), ("xmin", -84.4), ("xmax", -84.39), ("ymin", 0.0), ("ymax", 0.009)):
        z.writestr(name + ".npy", npy("<f8", (), [v]))
PY
python3 "$repo/datasets/make_terrain.py" "$work/dem.ply" --npz "$work/dem.npz" --step 2
python3 - "$work/dem.ply" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode().split()
nv, nf = int(header[header.index("vertex") + 1]), int(header[header.index("face") + 1])
assert (nv, nf) == (5 * 6, 2 * 4 * 5), (nv, nf)  # posts 0, 2, 4, 6, 8 by 0, 2, ..., 10
p = [struct.unpack_from("<3f", data, end + 12 * i) for i in range(nv)]
# At the equator a thousandth of a degree is 111.32 m east and 110.574 m north; every
# second post is kept.
assert abs(p[1][0] - 2 * 111.32) < 1e-3 and abs(p[6][1] - 2 * 110.574) < 1e-3, (p[1], p[6])
assert p[6 + 1][2] == 100 + 3 * 2 + 2 * 2, p[7]  # row 1, column 1 of the kept posts
print("ok: make_terrain.py wrote", nv, "vertices,", nf, "triangles")
PY
"$cli" simplify "$work/dem.ply" "$work/quads.ply" -f 10 -q --json >"$work/stats.json"
python3 -c 'import json, sys; s = json.load(open(sys.argv[1])); assert s["faces"] <= 10 and s["pure_quad"], s' \
  "$work/stats.json"
echo "ok: the CLI simplifies it"
