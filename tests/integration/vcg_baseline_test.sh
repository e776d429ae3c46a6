#!/usr/bin/env bash
# quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
# The vcglib baseline driver (bench/vcg_baseline.cpp) on an open grid and a closed torus:
# vcglib's half-edges must pass its own check before and after, the count must be
# reached, no vertex may be split as non-manifold, and `quadsimp stats` must measure the
# result. On the grid this fails when the driver builds the half-edges without
# face-face adjacency (the grid contracted to a point), and everywhere when it splits
# vertices whose faces form one fan: either would skew bench/RESULTS.md unseen.
#   vcg_baseline_test.sh QS_VCG_BASELINE QUADSIMP PROJECT_DIR
set -euo pipefail
baseline=$1 quadsimp=$2 project=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

python3 - "$tmp/grid.off" <<'EOF'
import sys
n = 8
with open(sys.argv[1], "w") as f:
    f.write(f"OFF\n{(n + 1) ** 2} {n * n} 0\n")
    for j in range(n + 1):
        for i in range(n + 1):
            f.write(f"{i} {j} 0\n")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            f.write(f"4 {a} {a + 1} {a + n + 2} {a + n + 1}\n")
EOF
python3 "$project/datasets/make_torus.py" "$tmp/torus.ply" 48 24

check() {  # mesh faces [driver options...]
  local mesh=$1 faces=$2
  shift 2
  local json
  json=$("$baseline" "$mesh" "$tmp/out.off" --faces "$faces" "$@")
  python3 - "$json" "$faces" <<'EOF'
import json, sys
r, faces = json.loads(sys.argv[1]), int(sys.argv[2])
assert r["halfedges_consistent"] == [True, True], r
assert r["faces"] == faces, r
assert r["not_quads"] == 0 and r["repeated_vertex"] == 0, r
assert r["nonmanifold_vertices"] == 0, r  # no vertex split on these: each vertex's faces form one fan
assert r["edges_over_two_faces"] == 0 and r["edges_same_direction"] == 0, r
EOF
  local stats
  stats=$("$quadsimp" stats "$mesh" "$tmp/out.off" --json --samples 2000)
  python3 - "$stats" "$faces" <<'EOF'
import json, sys
s, faces = json.loads(sys.argv[1]), int(sys.argv[2])
assert s["faces"] == faces and s["pure_quad"], s
assert s["flipped_faces"] == 0, s
assert s["hausdorff_e3"] < 100, s  # a tenth of the diagonal: nothing contracted
EOF
  echo "ok: $(basename "$mesh") to $faces quads $*"
}

check "$tmp/grid.off" 40
check "$tmp/torus.ply" 200
check "$tmp/torus.ply" 200 --unit-diagonal
check "$tmp/torus.ply" 200 --adaptive
