#!/usr/bin/env bash
# meshlabserver (MeshLab 2020.09) with the quadsimp plugin:
#  - the filter dump lists all four filters and their parameters;
#  - the example .mlx script simplifies a generated torus and the shared bunny, and the
#    PLY saved with face flags (-m ff) reads back as a valid pure quad mesh with the
#    target face count (within 1%), or with a share of the quads (TargetPerc) the CLI's;
#  - the plugin and the CLI give the same result for the same input and parameters, in
#    uniform mode and in adaptive mode with automatic halting (at two halting shares),
#    and MeshLab reads the CLI's PLY as its quads;
#  - a point cloud makes the filter fail with our message, without crashing MeshLab;
#  - a fin on an edge (three triangles on it) is removed, and MeshLab's log says so;
#  - a Moebius strip is cut open and simplified, and the log says so;
#  - a strip of triangles folded back onto a grid is laid flat, and the log says so;
#  - the quads come out as polygonal layers that MeshLab's polygon filters accept;
#  - MeshLab's own quads (its smart triangle pairing) are simplified;
#  - a coloured layer's quads take its vertex colours, and its face colours;
#  - a textured layer's quads take its texture;
#  - a cube keeps its edges and corners with a crease angle, as with the CLI's.
# Usage: meshlabserver_test.sh PLUGIN.so QUADSIMP_CLI REPO_DIR DATASETS_DIR
set -euo pipefail
plugin=$1 cli=$2 repo=$3 datasets=$4
here=$(cd "$(dirname "$0")" && pwd)
source "$here/meshlab_env.sh"
ml_env_setup "$plugin"
work=$ML_ROOT/work
mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
server() { ml_run meshlabserver "$@" >"$work/server.log" 2>&1; }
json() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }

# 1. The dump lists the four filters with their parameter labels.
server -d "$work/dump.txt" || true
for f in "Quad Mesh Simplification" "Convert to Pure Quad Mesh" "Compute Fitmaps" "Quad Mesh Quality"; do
  grep -q "section .* $f" "$work/dump.txt" || fail "filter '$f' missing from meshlabserver -d"
done
for p in "Adaptive (fitmaps)" "Target number of quads" "Automatic halting (adaptive)" \
         "Halting share (automatic halting)" "Fitmap tolerance tau" "Largest aspect (adaptive)" "Reach (adaptive)" \
         "Preserve boundary" "Keep tips" "Crease angle" "Fast (one pass)" "Fit vertices to the input" "Texture size" \
         "Reference mesh" "Distance samples"; do
  grep -q "$p" "$work/dump.txt" || fail "parameter '$p' missing from meshlabserver -d"
done

# 2. The example script on a generated torus and on the bunny.
python3 "$repo/datasets/make_torus.py" "$work/torus.ply" 96 48
script=$repo/plugin/meshlab2020/examples/quad_simplification.mlx
run_case() {  # input target
  local in=$1 target=$2 name
  name=$(basename "$in")
  sed "s/name=\"TargetFaceNum\" type=\"RichInt\" value=\"[0-9]*\"/name=\"TargetFaceNum\" type=\"RichInt\" value=\"$target\"/" \
    "$script" >"$work/script.mlx"
  if ! server -i "$in" -o "$work/$name.quads.ply" -m ff -s "$work/script.mlx"; then
    fail "meshlabserver failed on $name"; cat "$work/server.log"; return
  fi
  if ! "$cli" stats "$in" "$work/$name.quads.ply" --json --samples 50000 >"$work/$name.json"; then
    fail "$name: the saved result is not a valid pure quad mesh"; return
  fi
  local faces
  faces=$(json "$work/$name.json" faces)
  python3 -c "import sys; f,t=int(sys.argv[1]),int(sys.argv[2]); sys.exit(0 if abs(f-t) <= 0.01*t else 1)" \
    "$faces" "$target" || fail "$name: $faces faces, target $target"
  echo "ok: $name -> $faces quads (target $target)"
}
run_case "$work/torus.ply" 500
# A share of the quads instead of a number (TargetPerc), as the CLI's --faces 12.5%.
sed 's/name="TargetPerc" type="RichFloat" value="[0-9.]*"/name="TargetPerc" type="RichFloat" value="0.125"/' \
  "$script" >"$work/share.mlx"
"$cli" simplify "$work/torus.ply" "$work/share_cli.ply" --faces 12.5% -q >/dev/null
if server -i "$work/torus.ply" -o "$work/share.ply" -m ff -s "$work/share.mlx" &&
   "$cli" stats "$work/torus.ply" "$work/share.ply" --json --samples 20000 >"$work/share.json" &&
   "$cli" stats "$work/torus.ply" "$work/share_cli.ply" --json --samples 20000 >"$work/share_cli.json" &&
   [ "$(json "$work/share.json" faces)" = "$(json "$work/share_cli.json" faces)" ] &&
   [ "$(json "$work/share.json" faces)" = 576 ]; then  # an eighth of the torus's 4,608 quads
  echo "ok: TargetPerc 0.125 gives the CLI's --faces 12.5%: 576 quads"
else
  fail "TargetPerc did not give an eighth of the quads"; cat "$work/server.log"
fi
bunny=$(ml_bunny_ply "$datasets" "$cli" "$work/bunny_fitmap.ply") || fail "could not write the fallback bunny.ply"
if [ "$bunny" = "$work/bunny_fitmap.ply" ]; then
  # MeshLab saves glmark2's bunny again, so that the CLI reads the float coordinates
  # MeshLab holds.
  server -i "$bunny" -o "$work/bunny.ply" || fail "could not save the fallback bunny.ply"
  bunny=$work/bunny.ply
fi
run_case "$bunny" 3000

# 3. Same input, same parameters: the CLI gives the same mesh (up to float rounding of
#    the coordinates MeshLab stores).
"$cli" simplify "$bunny" "$work/cli.ply" --faces 3000 -q >/dev/null
"$cli" stats "$bunny" "$work/cli.ply" --json --samples 50000 >"$work/cli.json"
python3 - "$work/cli.json" "$work/$(basename "$bunny").json" <<'PY' || fail "plugin and CLI results differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for k in ("faces", "vertices", "max_valence", "regular_percent", "valence4_percent", "nonconvex_faces"):
    assert a[k] == b[k], (k, a[k], b[k])
for k in ("homeometry_min", "homeometry_max", "mean_edge", "hausdorff_e3", "rms_e3", "mean_to_ref_e3"):
    assert abs(a[k] - b[k]) <= 0.01 * max(abs(a[k]), 1e-9), (k, a[k], b[k])
print("ok: plugin and CLI agree:", {k: a[k] for k in ("faces", "regular_percent", "rms_e3")})
PY
# ... and MeshLab reads the CLI's file (binary PLY of doubles, quads as polygons) as its
# quads: saved again with faux flags, it holds the same 3000.
if server -i "$work/cli.ply" -o "$work/cli_resaved.ply" -m ff &&
   "$cli" stats "$bunny" "$work/cli_resaved.ply" --json --samples 20000 >"$work/cli_resaved.json" &&
   [ "$(json "$work/cli_resaved.json" faces)" = 3000 ] && [ "$(json "$work/cli_resaved.json" pure_quad)" = True ]; then
  echo "ok: MeshLab reads the CLI's PLY as 3000 quads"
else
  fail "MeshLab did not read the CLI's PLY as its quads"; cat "$work/server.log"
fi

# Runs the example script with some switches turned on, and the CLI with the matching
# options, on the bunny: $work/NAME.json and $work/cli_NAME.json hold their stats.
script_and_cli() {  # NAME "PARAM1 PARAM2..." CLI-OPTIONS... (input: $script_input, else the bunny)
  local name=$1 params=$2 p in=${script_input:-$bunny}
  shift 2
  cp "$script" "$work/$name.mlx"
  for p in $params; do
    sed -i "s/name=\"$p\" type=\"RichBool\" value=\"false\"/name=\"$p\" type=\"RichBool\" value=\"true\"/" "$work/$name.mlx"
    grep -q "name=\"$p\" type=\"RichBool\" value=\"true\"" "$work/$name.mlx" || { fail "$name: no $p in the script"; return 1; }
  done
  if ! server -i "$in" -o "$work/$name.ply" -m ff -s "$work/$name.mlx" </dev/null ||
     ! "$cli" stats "$in" "$work/$name.ply" --json --samples 50000 >"$work/$name.json"; then
    fail "$name script failed on $(basename "$in")"; cat "$work/server.log"; return 1
  fi
  "$cli" simplify "$in" "$work/cli_$name.ply" -q "$@" >/dev/null
  "$cli" stats "$in" "$work/cli_$name.ply" --json --samples 50000 >"$work/cli_$name.json"
}

# 3b. Adaptive mode with automatic halting from a script: it stops where the CLI does.
if script_and_cli adaptive "Adaptive AutoHalt" --adaptive --auto-halt; then
  python3 - "$work/cli_adaptive.json" "$work/adaptive.json" <<'PY' || fail "adaptive: plugin and CLI halt differently"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for k in ("faces", "vertices", "max_valence", "regular_percent"):
    assert a[k] == b[k], (k, a[k], b[k])
print("ok: adaptive, automatic halting: plugin and CLI stop at", a["faces"], "quads")
PY
fi

# Runs the adaptive script with one Float parameter set, and the CLI with the matching
# options, on the bunny; checks that both stop at the same mesh, then runs the Python
# check on stdin with the CLI's, the script's and the default script's stats as argv.
float_setting_and_cli() {  # NAME PARAM VALUE CLI-OPTIONS... (the check on stdin)
  local name=$1 param=$2 value=$3
  shift 3
  sed "s/name=\"$param\" type=\"RichFloat\" value=\"[0-9.]*\"/name=\"$param\" type=\"RichFloat\" value=\"$value\"/" \
    "$work/adaptive.mlx" >"$work/$name.mlx"
  if ! grep -q "name=\"$param\" type=\"RichFloat\" value=\"$value\"" "$work/$name.mlx"; then
    fail "$name: no $param in the script"; return
  fi
  if ! server -i "$bunny" -o "$work/$name.ply" -m ff -s "$work/$name.mlx" </dev/null ||
     ! "$cli" stats "$bunny" "$work/$name.ply" --json --samples 50000 >"$work/$name.json"; then
    fail "$name script failed on the bunny"; cat "$work/server.log"; return
  fi
  "$cli" simplify "$bunny" "$work/cli_$name.ply" -q --adaptive --auto-halt "$@" </dev/null >/dev/null
  "$cli" stats "$bunny" "$work/cli_$name.ply" --json --samples 50000 >"$work/cli_$name.json"
  python3 -c 'import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for k in ("faces", "vertices", "max_valence", "regular_percent"):
    assert a[k] == b[k], (k, a[k], b[k])' "$work/cli_$name.json" "$work/$name.json" </dev/null ||
    { fail "$name: plugin and CLI differ"; return; }
  python3 - "$work/cli_$name.json" "$work/$name.json" "$work/adaptive.json" || fail "$name: $param had no effect"
}

if [ -f "$work/adaptive.json" ]; then
  # 3b'. A smaller halting share from a script: it stops where the CLI's does, earlier.
  float_setting_and_cli share HaltShare 0.05 --halt-share 0.05 <<'PY'
import json, sys
a, b, default = (json.load(open(p)) for p in sys.argv[1:4])
assert b["faces"] > default["faces"], (b["faces"], default["faces"])
print("ok: halting share 0.05: plugin and CLI stop at", b["faces"], "quads, against", default["faces"])
PY
  # 3b''. Square quads from a script (MaxAspect 1): where the CLI's --max-aspect 1 stops,
  #       not where the default does.
  float_setting_and_cli square MaxAspect 1 --max-aspect 1 <<'PY'
import json, sys
a, b, default = (json.load(open(p)) for p in sys.argv[1:4])
assert (b["faces"], b["rms_e3"]) != (default["faces"], default["rms_e3"]), "MaxAspect 1 changed nothing"
print("ok: largest aspect 1: plugin and CLI stop at", b["faces"], "quads, against", default["faces"])
PY
  # 3b'''. No reach check from a script (Reach 0): where the CLI's --reach 0 stops.
  float_setting_and_cli noreach Reach 0 --reach 0 <<'PY'
import json, sys
a, b, default = (json.load(open(p)) for p in sys.argv[1:4])
assert (b["faces"], b["rms_e3"]) != (default["faces"], default["rms_e3"]), "Reach 0 changed nothing"
print("ok: reach 0: plugin and CLI stop at", b["faces"], "quads, against", default["faces"])
PY
fi

# 3c. The fit to the input from a script: the same as the CLI's, and closer than without.
if script_and_cli fit "FitToInput" --faces 3000 --fit-to-input; then
  python3 - "$work/cli_fit.json" "$work/fit.json" "$work/cli.json" <<'PY' || fail "fit: plugin and CLI differ"
import json, sys
a, b, plain = (json.load(open(p)) for p in sys.argv[1:4])
for k in ("faces", "vertices", "nonconvex_faces", "flipped_faces"):
    assert a[k] == b[k], (k, a[k], b[k])
assert abs(a["rms_e3"] - b["rms_e3"]) <= 0.01 * a["rms_e3"], (a["rms_e3"], b["rms_e3"])
assert b["rms_e3"] < 0.8 * plain["rms_e3"], (b["rms_e3"], plain["rms_e3"])
print("ok: fit to the input: plugin and CLI agree, RMS", plain["rms_e3"], "->", b["rms_e3"])
PY
fi

# 3d. Tips kept from a script, on the armadillo (its claws): the same as the CLI's
#     --keep-tips, and closer than the CLI without it.
armadillo=$datasets/armadillo.ply
if [ -f "$armadillo" ] && script_input=$armadillo script_and_cli tips "KeepTips" --faces 3000 --keep-tips; then
  "$cli" simplify "$armadillo" "$work/cli_plain_arm.ply" -q --faces 3000 >/dev/null
  "$cli" stats "$armadillo" "$work/cli_plain_arm.ply" --json --samples 50000 >"$work/cli_plain_arm.json"
  python3 - "$work/cli_tips.json" "$work/tips.json" "$work/cli_plain_arm.json" <<'PY' || fail "tips: plugin and CLI differ"
import json, sys
a, b, plain = (json.load(open(p)) for p in sys.argv[1:4])
for k in ("faces", "vertices", "max_valence", "regular_percent"):
    assert a[k] == b[k], (k, a[k], b[k])
assert b["rms_e3"] < 0.9 * plain["rms_e3"], (b["rms_e3"], plain["rms_e3"])
print("ok: tips kept: plugin and CLI agree, RMS", plain["rms_e3"], "->", b["rms_e3"])
PY
elif [ ! -f "$armadillo" ]; then
  echo "skip: no $armadillo for the tips case"
fi

# 4. Bad input: the filter refuses with our message, and MeshLab does not crash.
expect_refusal() {  # name message (the input is $work/NAME.ply)
  local name=$1 message=$2 code
  set +e
  ml_run meshlabserver -i "$work/$name.ply" -o "$work/${name}_out.ply" -s "$script" >"$work/$name.log" 2>&1
  code=$?
  set -e
  # A signal shows as 128+n; meshlabserver's own error exit is 255.
  if [ "$code" -gt 128 ] && [ "$code" -lt 192 ]; then fail "meshlabserver crashed on $name (exit $code)"; fi
  grep -q "$message" "$work/$name.log" || { fail "no clear message for $name"; cat "$work/$name.log"; }
}
# Runs the example script on $work/NAME.ply (to NAME_out.ply) and checks that MeshLab's
# log reports REPAIR of the input; false if meshlabserver failed.
simplified_with_repair() {  # name repair
  if ! server -i "$work/$1.ply" -o "$work/$1_out.ply" -m ff -s "$script"; then
    fail "meshlabserver failed on $1"; cat "$work/server.log"; return 1
  fi
  grep -q "$2" "$work/server.log" || { fail "$1: the repair is not in MeshLab's log"; cat "$work/server.log"; }
}
vertices='ply\nformat ascii 1.0\nelement vertex %s\nproperty float x\nproperty float y\nproperty float z\n'
printf "${vertices}end_header\n0 0 0\n1 0 0\n0 1 0\n" 3 >"$work/cloud.ply"
expect_refusal cloud "point cloud"
# Three triangles on one edge: the fin is removed, though it is the largest, the log says
# so, and the plane's two triangles become one quad.
printf "${vertices}element face 3\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0.5 0 3\n3 0 1 2\n3 0 1 4\n3 1 0 3\n" 5 >"$work/fin.ply"
if simplified_with_repair fin "1 faces removed at edges shared by more than two triangles"; then
  # One quad, on the plane (measured against the plane alone, not against our own
  # cleaning of the fin): a fin left in the result would lie up to 3 units off it.
  printf "${vertices}element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n3 0 1 2\n3 1 0 3\n" 4 >"$work/plane.ply"
  faces=$("$cli" stats "$work/plane.ply" "$work/fin_out.ply" --json --samples 1000 |
          python3 -c "import json,sys; s=json.load(sys.stdin); print(s['faces'] if s['max_to_ref_e3'] < 1 else 'off the plane')") ||
    fail "fin: the result is not a valid pure quad mesh"
  [ "${faces:-0}" = 1 ] && echo "ok: fin removed, 1 quad" || fail "fin: ${faces:-no} quads, not 1 on the plane"
fi

# A Moebius strip (96 x 8 quads, split) is not orientable: loading cuts it open across its
# twist, the log says so, and the result is a valid pure quad mesh of the script's target.
python3 - "$work/moebius.ply" <<'PY'
import math, sys
along, across = 96, 8
points, faces = [], []
for i in range(along):
    u = 2 * math.pi * i / along
    for j in range(across + 1):
        s = 0.6 * j / across - 0.3
        points.append(((1 + s * math.cos(u / 2)) * math.cos(u), (1 + s * math.cos(u / 2)) * math.sin(u),
                       s * math.sin(u / 2)))
vid = lambda i, j: i * (across + 1) + j if i < along else across - j  # row `along` is row 0 turned over
for i in range(along):
    for j in range(across):
        faces += [(vid(i, j), vid(i + 1, j), vid(i, j + 1)), (vid(i, j + 1), vid(i + 1, j), vid(i + 1, j + 1))]
with open(sys.argv[1], "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
            "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(points), len(faces)))
    f.writelines("%.7f %.7f %.7f\n" % p for p in points)
    f.writelines("3 %d %d %d\n" % t for t in faces)
PY
sed 's/name="TargetFaceNum" type="RichInt" value="[0-9]*"/name="TargetFaceNum" type="RichInt" value="150"/' \
  "$script" >"$work/moebius.mlx"
if ! server -i "$work/moebius.ply" -o "$work/moebius_out.ply" -m ff -s "$work/moebius.mlx"; then
  fail "meshlabserver failed on the Moebius strip"; cat "$work/server.log"
else
  grep -q "the surface is not orientable (a Moebius-like strip): cut open along" "$work/server.log" ||
    { fail "moebius: the cut is not in MeshLab's log"; cat "$work/server.log"; }
  faces=$("$cli" stats "$work/moebius.ply" "$work/moebius_out.ply" --json --samples 1000 |
    python3 -c "import json,sys; print(json.load(sys.stdin)['faces'])") ||
    fail "moebius: the result is not a valid pure quad mesh"
  [ "${faces:-0}" = 150 ] && echo "ok: Moebius strip cut open, $faces quads" ||
    fail "moebius: ${faces:-no} quads, not 150"
fi

# A strip of triangles folded back onto a 128 x 128 grid (five vertices in a column
# pushed one and a half cells past their neighbours): loading lays it flat, the log says
# so, and no quad of the result is flipped, non-convex or folded over the flat grid.
python3 - "$work" <<'PY'
import sys
n, work = 128, sys.argv[1]
points = [[i / n, j / n, 0.0] for j in range(n + 1) for i in range(n + 1)]
faces = []
for j in range(n):
    for i in range(n):
        a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
        faces += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
for name in ("flat", "folded"):
    with open(f"{work}/{name}.ply", "w") as out:
        out.write(f"ply\nformat ascii 1.0\nelement vertex {len(points)}\nproperty float x\nproperty float y\n"
                  f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        out.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in points)
        out.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)
    for j in range(40, 45):
        points[j * (n + 1) + 40][0] += 1.5 / n
PY
if simplified_with_repair folded "1 patches of triangles folded back onto the surface laid flat"; then
  bad=$("$cli" stats "$work/flat.ply" "$work/folded_out.ply" --json --samples 1000 |
        python3 -c "import json,sys; s=json.load(sys.stdin); print(s['flipped_faces'] + s['nonconvex_faces'] + s['folded_faces'])") ||
    fail "fold: the result is not a valid pure quad mesh"
  [ "${bad:-1}" = 0 ] && echo "ok: fold laid flat, every quad sound" || fail "fold: ${bad:-no count of} bad quads"
fi

# 5. The other three filters, chained on the torus: convert (in place), fitmaps, quality.
cat >"$work/others.mlx" <<'MLX'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Convert to Pure Quad Mesh">
  <Param name="CreaseAngle" type="RichFloat" value="0"/>
  <Param name="TextureSize" type="RichInt" value="4096"/>
 </filter>
 <filter name="Compute Fitmaps">
  <Param name="Tau" type="RichFloat" value="0.05"/>
 </filter>
 <filter name="Quad Mesh Quality">
  <Param name="ReferenceMesh" type="RichMesh" value="0"/>
  <Param name="SampleNum" type="RichInt" value="20000"/>
 </filter>
</FilterScript>
MLX
if server -i "$work/torus.ply" -o "$work/torus_converted.ply" -m ff vq -s "$work/others.mlx" -l "$work/others.log"; then
  grep -q "fitmaps of" "$work/others.log" || fail "Compute Fitmaps did not report"
  grep -q "Hausdorff" "$work/others.log" || fail "Quad Mesh Quality did not report"
  grep -q "property float quality" "$work/torus_converted.ply" || fail "no vertex quality (S fitmap) saved"
  "$cli" stats "$work/torus.ply" "$work/torus_converted.ply" --json --samples 20000 >"$work/conv.json" \
    || fail "the converted torus is not a valid pure quad mesh"
  [ "$(json "$work/conv.json" faces)" = 4608 ] || fail "the torus should convert to 4608 quads"
  echo "ok: convert, fitmaps and quality filters"
else
  fail "the convert/fitmaps/quality script failed"; cat "$work/server.log"
fi

# The example script's simplification filter, to chain with MeshLab's own filters.
simplification=$(sed -n '/<filter name="Quad Mesh Simplification">/,/<\/filter>/p' "$script")

# 6. The layers come out polygonal, as MeshLab's own quad filters make them: MeshLab's
#    polygonal planarity quality (which refuses triangle-only layers, and walks the faux
#    edges through face-face adjacency) runs on the simplified and the converted torus.
planarity='<filter name="Per Face Quality according to Triangle shape and aspect ratio">
  <Param name="Metric" type="RichEnum" value="6" enum_cardinality="8" enum_val0="area/max side"
   enum_val1="inradius/circumradius" enum_val2="Mean ratio" enum_val3="Area" enum_val4="Texture Angle Distortion"
   enum_val5="Texture Area Distortion" enum_val6="Polygonal planarity (max)" enum_val7="Polygonal planarity (relative)"/>
 </filter>'
convert='<filter name="Convert to Pure Quad Mesh">
  <Param name="CreaseAngle" type="RichFloat" value="0"/>
  <Param name="TextureSize" type="RichInt" value="4096"/>
 </filter>'
for first in "${simplification/value=\"3000\"/value=\"500\"}" "$convert"; do
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n%s\n %s\n</FilterScript>\n' "$first" "$planarity" >"$work/planar.mlx"
  if server -i "$work/torus.ply" -o "$work/planar.ply" -m ff fq -s "$work/planar.mlx" -l "$work/planar.log" &&
     grep -q "property float quality" "$work/planar.ply"; then
    echo "ok: MeshLab's polygonal planarity runs after '$(echo "$first" | head -1 | cut -d'"' -f2)'"
  else
    fail "polygonal planarity refused or failed after: $(echo "$first" | head -1)"; cat "$work/server.log"
  fi
done

# 7. MeshLab's own quads as input: its smart triangle pairing leaves doublets (two quads on
#    two shared edges) in the bunny, which our reference triangles once made non-manifold.
{
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n <filter name="Tri to Quad by smart triangle pairing"/>\n'
  printf '%s\n</FilterScript>\n' "$simplification"
} >"$work/paired.mlx"
if server -i "$bunny" -o "$work/paired.ply" -m ff -s "$work/paired.mlx" &&
   "$cli" stats "$bunny" "$work/paired.ply" --json --samples 20000 >"$work/paired.json" &&
   [ "$(json "$work/paired.json" faces)" = 3000 ]; then
  echo "ok: MeshLab's smart triangle pairing, then ours: 3000 quads"
else
  fail "MeshLab's paired quads were not simplified"; cat "$work/server.log"
fi

# 8. A coloured layer's quads take its colours: the torus coloured by MeshLab's own colour
#    function (red along x, green along y), simplified and saved with its vertex colours;
#    each vertex's colour must match its position (two byte roundings plus interpolation).
{
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n <filter name="Per Vertex Color Function">\n'
  printf '  <Param name="x" type="RichString" value="255*(x+1.35)/2.7"/>\n'
  printf '  <Param name="y" type="RichString" value="255*(y+1.35)/2.7"/>\n'
  printf '  <Param name="z" type="RichString" value="0"/>\n  <Param name="a" type="RichString" value="255"/>\n'
  printf '  <Param name="onselected" type="RichBool" value="false"/>\n </filter>\n'
  printf '%s\n</FilterScript>\n' "${simplification/value=\"3000\"/value=\"500\"}"
} >"$work/coloured.mlx"
if server -i "$work/torus.ply" -o "$work/coloured.ply" -m vc ff -s "$work/coloured.mlx" &&
   python3 - "$work/coloured.ply" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode("ascii").split("\n")
assert "format binary_little_endian 1.0" in header, header[:3]
count = next(int(l.split()[2]) for l in header if l.startswith("element vertex"))
props = []
for line in header[header.index(next(l for l in header if l.startswith("element vertex"))) + 1:]:
    if not line.startswith("property"):
        break
    props.append(line.split()[1:])
code = {"float": "f", "double": "d", "uchar": "B", "int": "i", "uint": "I"}
fmt = "<" + "".join(code[t] for t, _ in props)
names = [n for _, n in props]
assert {"red", "green", "blue"} <= set(names), names
worst = 0.0
for v in range(count):
    row = dict(zip(names, struct.unpack_from(fmt, data, end + v * struct.calcsize(fmt))))
    worst = max(worst, abs(row["red"] / 255 - (row["x"] + 1.35) / 2.7), abs(row["green"] / 255 - (row["y"] + 1.35) / 2.7))
    assert row["blue"] == 0, row
print(f"{count} vertices, largest colour error {255 * worst:.2f} / 255")
sys.exit(0 if worst < 3 / 255 else 1)
PY
then
  echo "ok: the quads take the layer's vertex colours"
else
  fail "the quads did not take the coloured torus's colours"; cat "$work/server.log"
fi

# 9. A layer's face colours reach its quads: the torus's faces coloured by MeshLab's own
#    face colour function (red where x > 0, blue elsewhere), simplified and saved with its
#    face colours; each triangle (both of a quad) must take its half's colour, quads across
#    the line (within a quad's size) either.
{
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n <filter name="Per Face Color Function">\n'
  printf '  <Param name="r" type="RichString" value="(x0+x1+x2)/3 &gt; 0 ? 255 : 0"/>\n'
  printf '  <Param name="g" type="RichString" value="0"/>\n'
  printf '  <Param name="b" type="RichString" value="(x0+x1+x2)/3 &gt; 0 ? 0 : 255"/>\n'
  printf '  <Param name="a" type="RichString" value="255"/>\n'
  printf '  <Param name="onselected" type="RichBool" value="false"/>\n </filter>\n'
  printf '%s\n</FilterScript>\n' "${simplification/value=\"3000\"/value=\"500\"}"
} >"$work/faces.mlx"
if server -i "$work/torus.ply" -o "$work/faces.ply" -m fc -s "$work/faces.mlx" &&
   python3 - "$work/faces.ply" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode("ascii").split("\n")
assert "format binary_little_endian 1.0" in header, header[:3]
code = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I", "float": "f", "double": "d"}
elements = []  # (name, count, [(type, name, list count type or None)])
for line in header:
    w = line.split()
    if w[:1] == ["element"]:
        elements.append((w[1], int(w[2]), []))
    elif w[:1] == ["property"]:
        elements[-1][2].append((w[-2], w[-1], w[2] if w[1] == "list" else None))
pos, points, worst_wrong, faces = end, [], 0, 0
for name, count, props in elements:
    for _ in range(count):
        row = {}
        for kind, prop, list_count in props:
            if list_count:
                (n,) = struct.unpack_from("<" + code[list_count], data, pos)
                pos += struct.calcsize(code[list_count])
                row[prop] = struct.unpack_from("<%d%s" % (n, code[kind]), data, pos)
                pos += n * struct.calcsize(code[kind])
            else:
                (row[prop],) = struct.unpack_from("<" + code[kind], data, pos)
                pos += struct.calcsize(code[kind])
        if name == "vertex":
            points.append(row["x"])
        elif name == "face":
            faces += 1
            x = sum(points[i] for i in row["vertex_indices"]) / 3
            colour = (row["red"], row["green"], row["blue"])
            assert colour in ((255, 0, 0), (0, 0, 255)), colour
            if colour != ((255, 0, 0) if x > 0 else (0, 0, 255)):
                worst_wrong = max(worst_wrong, abs(x))
# 500 quads over a torus 2.7 across: a quad is about 0.2 wide.
print(f"{faces} triangles; the farthest from x = 0 of another half's colour: {worst_wrong:.3f}")
sys.exit(0 if faces == 1000 and worst_wrong < 0.2 else 1)
PY
then
  echo "ok: the quads take the layer's face colours"
else
  fail "the quads did not take the torus's face colours"; cat "$work/server.log"
fi

# 10. A layer's texture reaches its quads, on the sphere of textured_sphere.py (as PLY:
#     MeshLab 2020.09 here reads no OBJ). The quads' texture is written beside the input's
#     file, and the quads saved with their wedge coordinates show it: MeshLab 2025.07's own
#     texture transfer (pymeshlab) sees on the input's vertices the same colours from them as
#     from the input, within 3 units of 255 away from the seam and the poles.
mkdir -p "$work/tex"
python3 "$here/textured_sphere.py" "$work/tex" ply >/dev/null
printf '<!DOCTYPE FilterScript>\n<FilterScript>\n%s\n</FilterScript>\n' \
  "${simplification/value=\"3000\"/value=\"500\"}" >"$work/tex.mlx"
if server -i "$work/tex/lonlat.ply" -o "$work/tex/quads.ply" -m wt -s "$work/tex.mlx" &&
   grep -q "texture baked onto the quads: lonlat_quads_texture.png" "$work/server.log" &&
   [ -f "$work/tex/lonlat_quads_texture.png" ] &&
   "$repo/.venv/bin/python" - "$work/tex" <<'PY'
import pathlib, sys
import numpy as np
import pymeshlab
folder = pathlib.Path(sys.argv[1])
ms = pymeshlab.MeshSet()
ms.load_new_mesh(str(folder / "lonlat.ply"))
ms.load_new_mesh(str(folder / "quads.ply"))
assert ms.current_mesh().has_wedge_tex_coord() and ms.current_mesh().texture_number() == 1
seen = []
for source in (0, 1):
    ms.load_new_mesh(str(folder / "lonlat.ply"))
    ms.transfer_texture_to_color_per_vertex(sourcemesh=source, targetmesh=ms.current_mesh_id())
    seen.append(ms.current_mesh().vertex_color_matrix()[:, :3])
v = ms.current_mesh().vertex_matrix()
off = np.abs(seen[0] - seen[1]).max(axis=1) * 255
away = (np.abs(v[:, 2]) < 0.9) & ~((v[:, 0] > 0) & (np.abs(v[:, 1]) < 0.15))
print(f"{away.sum()} vertices away from the seam and poles: at most {off[away].max():.0f} of 255 off")
sys.exit(0 if away.mean() > 0.6 and off[away].max() <= 3 else 1)
PY
then
  echo "ok: the quads take the layer's texture"
else
  fail "the quads did not take the sphere's texture"; cat "$work/server.log"
fi
# MeshLab reads the CLI's textured PLY (quads as triangle pairs with a faux diagonal, as it
# writes them) with its texture: saved again, the texture file and coordinates are there.
if "$cli" simplify "$work/tex/lonlat.ply" "$work/tex/cli.ply" --faces 500 -q >/dev/null &&
   server -i "$work/tex/cli.ply" -o "$work/tex/cli_again.ply" -m wt ff &&
   head -c 2000 "$work/tex/cli_again.ply" | grep -a -q "TextureFile cli_texture.png" &&
   head -c 2000 "$work/tex/cli_again.ply" | grep -a -q "property list uchar float texcoord" &&
   head -c 2000 "$work/tex/cli_again.ply" | grep -a -q "element face 1000"; then
  echo "ok: MeshLab reads the CLI's textured PLY with its texture"
else
  fail "MeshLab did not read the CLI's textured PLY with its texture"; cat "$work/server.log"
fi
# Run again, the first result's texture is kept: the second goes to a name of its own.
if server -i "$work/tex/lonlat.ply" -o "$work/tex/again.ply" -m wt -s "$work/tex.mlx" &&
   grep -q "texture baked onto the quads: lonlat_quads_texture_2.png" "$work/server.log" &&
   [ -f "$work/tex/lonlat_quads_texture_2.png" ] && grep -q "lonlat_quads_texture_2.png" "$work/tex/again.ply" &&
   grep -q "lonlat_quads_texture.png" "$work/tex/quads.ply"; then
  echo "ok: a second result's texture does not replace the first's"
else
  fail "a second result's texture replaced the first's"; cat "$work/server.log"
fi
# The texture size from a script bounds the quads' texture, which is wider by default.
texels() { sed -n 's/.*texture baked onto the quads: [^,]*, \([0-9]*\) x \([0-9]*\) texels.*/\1 \2/p' "$1"; }
cp "$work/server.log" "$work/tex_default.log"
sed 's/name="TextureSize" type="RichInt" value="4096"/name="TextureSize" type="RichInt" value="128"/' \
  "$work/tex.mlx" >"$work/tex128.mlx"
if server -i "$work/tex/lonlat.ply" -o "$work/tex/small.ply" -m wt -s "$work/tex128.mlx" &&
   read -r w h <<<"$(texels "$work/server.log")" && read -r dw dh <<<"$(texels "$work/tex_default.log")" &&
   [ "$w" -le 128 ] && [ "$h" -le 128 ] && [ "$dw" -gt 128 ]; then
  echo "ok: the texture size bounds the quads' texture ($w x $h texels; $dw x $dh by default)"
else
  fail "the texture size did not bound the quads' texture"; cat "$work/server.log"
fi

# 11. A crease angle from a script: a cube keeps its 8 corners and its edges (no distance
#     to it), as the CLI's --crease-angle does; the conversion alone pairs nothing across.
python3 "$here/cube_ply.py" "$work/cube.ply" 12
sed -e 's/name="TargetFaceNum" type="RichInt" value="[0-9]*"/name="TargetFaceNum" type="RichInt" value="100"/' \
    -e 's/name="CreaseAngle" type="RichFloat" value="[0-9.]*"/name="CreaseAngle" type="RichFloat" value="30"/' \
    "$script" >"$work/crease.mlx"
"$cli" simplify "$work/cube.ply" "$work/cube_cli.ply" --faces 100 --crease-angle 30 -q >/dev/null
if grep -q 'name="CreaseAngle" type="RichFloat" value="30"' "$work/crease.mlx" &&
   server -i "$work/cube.ply" -o "$work/cube_quads.ply" -m ff -s "$work/crease.mlx" &&
   "$cli" stats "$work/cube.ply" "$work/cube_quads.ply" --json --samples 20000 >"$work/cube.json" &&
   "$cli" stats "$work/cube.ply" "$work/cube_cli.ply" --json --samples 20000 >"$work/cube_cli.json" &&
   python3 - "$work/cube_cli.json" "$work/cube.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for k in ("faces", "vertices", "max_valence", "regular_percent"):
    assert a[k] == b[k], (k, a[k], b[k])
assert b["hausdorff_e3"] < 1e-3, b["hausdorff_e3"]
print("ok: crease angle 30: plugin and CLI give", b["faces"], "quads on the cube, Hausdorff", b["hausdorff_e3"])
PY
then
  :
else
  fail "the crease angle did not keep the cube's edges as the CLI does"; cat "$work/server.log"
fi
printf '<!DOCTYPE FilterScript>\n<FilterScript>\n %s\n</FilterScript>\n' \
  "${convert/value=\"0\"/value=\"30\"}" >"$work/crease_convert.mlx"
if server -i "$work/cube.ply" -o "$work/cube_converted.ply" -m ff -s "$work/crease_convert.mlx" -l "$work/crease_convert.log" &&
   "$cli" stats "$work/cube.ply" "$work/cube_converted.ply" --json --samples 20000 >"$work/cube_conv.json" &&
   [ "$(json "$work/cube_conv.json" faces)" = 864 ] &&
   python3 -c "import json,sys; sys.exit(0 if json.load(open(sys.argv[1]))['hausdorff_e3'] < 1e-3 else 1)" \
     "$work/cube_conv.json"; then
  echo "ok: the conversion with a crease angle keeps the cube flat on its sides: 864 quads"
else
  fail "the conversion with a crease angle"; cat "$work/server.log"
fi

# 12. Quads left folded over a CAD cylinder's rims (README, Limits) are selected in the
#     result: saved with face flags, both triangles of each carry vcglib's selection bit
#     (0x20), as many as the log's count says, and no other.
python3 "$here/cad_cylinder_ply.py" "$work/cylinder.ply" 64
sed 's/name="TargetFaceNum" type="RichInt" value="[0-9]*"/name="TargetFaceNum" type="RichInt" value="100"/' \
  "$script" >"$work/cylinder.mlx"
flawed=
if server -i "$work/cylinder.ply" -o "$work/cylinder_out.ply" -m ff -s "$work/cylinder.mlx"; then
  flawed=$(sed -n 's/.*the \([0-9]*\) quads counted above (.*) are selected in the new layer.*/\1/p' \
             "$work/server.log" | head -1)
fi
if [ -n "$flawed" ] && [ "$flawed" -gt 0 ] && python3 - "$work/cylinder_out.ply" "$flawed" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode("ascii").split("\n")
expected = ["format binary_little_endian 1.0", "property float x", "property float y", "property float z",
            "property list uchar int vertex_indices", "property int flags"]
assert all(line in header for line in expected), header
vertices = int(next(l for l in header if l.startswith("element vertex")).split()[2])
faces = int(next(l for l in header if l.startswith("element face")).split()[2])
assert len([l for l in header if l.startswith("property")]) == 5, header  # nothing else to skip
pos, selected = end + 12 * vertices, []
for t in range(faces):
    pos += 1 + 4 * data[pos]
    (flags,) = struct.unpack_from("<i", data, pos)
    pos += 4
    if flags & 0x20:
        selected.append(t)
# assign_quads() writes each quad's two triangles in turn.
assert len(selected) == 2 * int(sys.argv[2]) and all(t ^ 1 in selected for t in selected), selected
print(f"ok: the {sys.argv[2]} folded quads of the cylinder are selected ({len(selected)} triangles)")
PY
then
  :
else
  fail "the flawed quads are not selected as the log says (${flawed:-no count})"; cat "$work/server.log"
fi

if [ "$failures" -gt 0 ]; then echo "$failures failed"; exit 1; fi
echo "meshlabserver tests passed"
