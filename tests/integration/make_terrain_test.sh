#!/usr/bin/env bash
# datasets/make_terrain.py on a small DEM written here in matplotlib's npz layout (no
# download): the mesh has one vertex per kept post, two triangles per cell, the heights
# in place, posts spaced as the degrees say, and the CLI reads and simplifies it.
# Usage: make_terrain_test.sh REPO_DIR QUADSIMP_CLI PYTHON (a Python with numpy)
set -euo pipefail
repo=$1 cli=$2 python=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$python" - "$work/dem.npz" <<'PY'
import sys, numpy as np
rows, cols = 9, 11
r, c = np.mgrid[0:rows, 0:cols]
np.savez(sys.argv[1], elevation=(100 + 3 * r + 2 * c).astype(np.int16), dx=0.001, dy=0.001,
         xmin=-84.4, xmax=-84.39, ymin=0.0, ymax=0.009)
PY
"$python" "$repo/datasets/make_terrain.py" "$work/dem.ply" --npz "$work/dem.npz" --step 2
"$python" - "$work/dem.ply" <<'PY'
import sys, numpy as np
data = open(sys.argv[1], "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode().split()
nv, nf = int(header[header.index("vertex") + 1]), int(header[header.index("face") + 1])
assert (nv, nf) == (5 * 6, 2 * 4 * 5), (nv, nf)  # posts 0, 2, 4, 6, 8 by 0, 2, ..., 10
p = np.frombuffer(data, "<f4", 3 * nv, end).reshape(nv, 3)
# At the equator a thousandth of a degree is 111.32 m east and 110.574 m north; every
# second post is kept.
assert abs(p[1, 0] - 2 * 111.32) < 1e-3 and abs(p[6, 1] - 2 * 110.574) < 1e-3, (p[1], p[6])
assert p[6 + 1, 2] == 100 + 3 * 2 + 2 * 2, p[7]  # row 1, column 1 of the kept posts
faces = np.frombuffer(data, [("n", "u1"), ("v", "<i4", 3)], nf, end + 12 * nv)
assert (faces["n"] == 3).all() and faces["v"].min() == 0 and faces["v"].max() == nv - 1
print("ok: make_terrain.py wrote", nv, "vertices,", nf, "triangles")
PY
"$cli" simplify "$work/dem.ply" "$work/quads.ply" -f 10 -q --json >"$work/stats.json"
"$python" -c 'import json, sys; s = json.load(open(sys.argv[1])); assert s["faces"] <= 10 and s["pure_quad"], s' \
  "$work/stats.json"
echo "ok: the CLI simplifies it"
