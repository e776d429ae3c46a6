#!/usr/bin/env bash
# `cmake --install` puts the MeshLab 2020.09 plugin where Debian's MeshLab loads it
# (staged with DESTDIR, so the test does not touch the system), and the folder can be
# changed with QS_PLUGIN_2020_INSTALL_DIR. It also installs the library as a CMake
# package: a project of its own (consumer/) finds it, builds against it, and runs.
# Usage: install_test.sh BUILD_DIR
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
stage=$(mktemp -d /tmp/qs_install.XXXXXX)
trap 'rm -rf "$stage"' EXIT
DESTDIR=$stage cmake --install "$build" >/dev/null
plugin=$stage/usr/lib/x86_64-linux-gnu/meshlab/plugins/libfilter_quadsimp.so
[ -f "$plugin" ] || { echo "FAIL: $plugin not installed"; find "$stage" -type f; exit 1; }
[ -x "$stage/usr/local/bin/quadsimp" ] || { echo "FAIL: quadsimp not installed in bin/"; exit 1; }
echo "ok: $plugin"

prefix=$stage/usr/local
for f in lib/libquadsimp_core.a lib/libquadsimp_io.a lib/libquadsimp_remesh.a lib/cmake/quadsimp/quadsimpConfig.cmake \
         include/quadsimp/simplify/pipeline.h include/quadsimp/io/mesh_io.h include/quadsimp/remesh/isotropic_remesh.h; do
  [ -f "$prefix/$f" ] || { echo "FAIL: $f not installed"; exit 1; }
done
for f in text_lines.h text_readers.h atomic_file.h; do  # the readers' and writers' own helpers
  [ ! -e "$prefix/include/quadsimp/io/$f" ] || { echo "FAIL: the internal $f was installed"; exit 1; }
done
# The consumer is built from a copy, away from the source tree and its build, so that
# only the installed package can be found.
cp -r "$here/consumer" "$stage/consumer"
if ! cmake -S "$stage/consumer" -B "$stage/consumer/build" -DCMAKE_PREFIX_PATH="$prefix" \
       -DCMAKE_BUILD_TYPE=Release >"$stage/configure.log" 2>&1 ||
   ! cmake --build "$stage/consumer/build" >"$stage/build.log" 2>&1; then
  echo "FAIL: a project using the installed package did not build"; cat "$stage"/*.log; exit 1
fi
python3 "$here/../../datasets/make_torus.py" "$stage/torus.ply" 48 24 >/dev/null
for mode in uniform adaptive remeshed; do
  out=$("$stage/consumer/build/simplify_file" "$stage/torus.ply" "$stage/quads.obj" 200 $mode)
  echo "$out"
  [[ $out == "200 quads,"* ]] || { echo "FAIL: the consumer's $mode run did not give 200 quads"; exit 1; }
  [ "$(grep -c '^f ' "$stage/quads.obj")" = 200 ] || { echo "FAIL: its file does not hold 200 quads"; exit 1; }
done
out=$("$stage/consumer/build/simplify_grid" 150)
[ "$out" = "150 quads" ] || { echo "FAIL: the core alone gave '$out', not 150 quads"; exit 1; }
echo "ok: a CMake project finds quadsimp::io, quadsimp::remesh and quadsimp::core in the installed package, builds and simplifies"
