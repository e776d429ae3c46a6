#!/usr/bin/env bash
# The main job on the default mesh: set up, build, and simplify the Stanford bunny
# shipped by Debian's glmark2-data.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/setup.sh"
"$here/scripts/build.sh"
input=/usr/share/glmark2/models/bunny.obj
output="$here/out/bunny_quads.ply"
mkdir -p "$here/out"
"$here/build/src/quadsimp" simplify "$input" "$output" --faces 5000 --stats
echo "result: $output (5,000 quads; open it in MeshLab, or: build/src/quadsimp stats $input $output)"
