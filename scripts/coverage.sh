#!/usr/bin/env bash
# Line coverage of the library, the CLI and the plugins' shared code (plugin/common) by the
# unit and CLI tests (qs_tests): builds build-coverage/ with gcc's --coverage, runs the
# tests (about 7 minutes on 2 cores, the build included), and lists each source file of
# src/ and plugin/common/ with lines no test ran, worst first; with -v, the lines
# themselves. Needs scripts/setup.sh's packages only (gcov comes with gcc). The plugins'
# adapters (plugin/meshlab20xx) are tested through MeshLab, not here.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$here/build-coverage"
verbose=0
[[ "${1:-}" == "-v" ]] && verbose=1

cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS="--coverage -O1" \
  -DCMAKE_EXE_LINKER_FLAGS="--coverage" -DQS_BUILD_PLUGIN_2020=OFF -DQS_BUILD_PLUGIN_2025=OFF \
  -DQS_BUILD_BENCH=OFF >/dev/null
# Counts of an earlier build go first: the build's own test discovery runs qs_tests, which
# merged into them with a warning per changed file.
find "$build" -name '*.gcda' -delete 2>/dev/null || true
cmake --build "$build" --target qs_tests quadsimp --parallel "$(nproc)"
find "$build" -name '*.gcda' -delete
# A failing test still leaves its coverage: report it, and fail at the end.
status=0
(cd "$build" && tests/qs_tests --gtest_brief=1) || status=$?

report="$build/gcov"
rm -rf "$report" && mkdir -p "$report"
cd "$report"
# -p keeps the paths in the names, so that headers and sources of one name stay apart.
find "$build/src" "$build/tests" -name '*.gcda' -not -path '*/.deps/*' -exec gcov -p -o {} {} \; >/dev/null 2>&1 || true
# Per-object runs of gcov each write a source's file; a source compiled once has one, and
# plugin/common's headers are compiled into qs_tests alone.
files() { ls *'#src#'*.cpp.gcov *'#plugin#common#'*.gcov 2>/dev/null || true; }
prefix="${here//\//#}#"  # gcov -p writes each '/' of a source's path as '#'
name() { local f=${1#"$prefix"}; f=${f//#//}; echo "${f%.gcov}"; }
for f in $(files); do
  total=$(grep -cE '^ +([0-9]+\*?|#####):' "$f" || true)
  missed=$(grep -cE '^ +#####:' "$f" || true)
  echo "$missed $total $(name "$f")"
done | sort -rn | awk '$1 > 0 { printf "%5d of %5d lines not run  %s\n", $1, $2, $3 }'
if ((verbose)); then
  for f in $(files); do
    grep -qE '^ +#####:' "$f" || continue
    echo "== $(name "$f")"
    grep -E '^ +#####:' "$f" | cut -c1-160
  done
fi
exit "$status"
