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
"$here/build/src/quadsimp" convert "$input" "$output"
echo "result: $output"
