#!/usr/bin/env bash
# Coverage-guided fuzzing (libFuzzer, with AddressSanitizer and UndefinedBehaviorSanitizer)
# of the mesh readers and of the whole run on small meshes (tests/fuzz/): builds
# build-fuzz/ with clang, writes a seed corpus of small files in every format, and runs
# each target for SECONDS (default 600) on all cores. Inputs that crash, hang (over 20 s),
# allocate over 2 GB or throw anything but a refusal go to build-fuzz/findings/TARGET/;
# replay one with `build-fuzz/tests/fuzz/TARGET FILE`. The corpus grows in
# build-fuzz/corpus/TARGET/ and a later run goes on from it. Needs scripts/setup.sh's
# packages, and Debian's clang (libFuzzer), which it installs when missing.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]    TARGET: read_mesh_fuzzer, simplify_fuzzer
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$here/build-fuzz"
seconds=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(read_mesh_fuzzer simplify_fuzzer)
if ! command -v clang++ >/dev/null; then  # libFuzzer comes with Debian's clang
  [ "$(id -u)" = 0 ] || { echo "fuzz: clang++ not found; as root: apt-get install clang" >&2; exit 1; }
  echo "fuzz: installing Debian's clang (libFuzzer)"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends clang >/dev/null
fi

flags="-O1 -g -fsanitize=address,undefined,fuzzer-no-link -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DQS_BUILD_FUZZERS=ON -DQS_BUILD_TESTS=OFF \
  -DQS_BUILD_BENCH=OFF -DQS_BUILD_CLI=OFF -DQS_BUILD_PLUGIN_2020=OFF -DQS_BUILD_PLUGIN_2025=OFF >/dev/null
cmake --build "$build" --target "${targets[@]}" --parallel "$(nproc)"
python3 "$here/tests/fuzz/make_seeds.py" "$build/seeds"

status=0
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t" "$build/findings/$t"
  # The simplify fuzzer's meshes stay small: a few hundred triangles at most.
  max_len=$([ "$t" = simplify_fuzzer ] && echo 16384 || echo 65536)
  echo "fuzz: $t for $seconds s"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/tests/fuzz/$t" "$build/corpus/$t" "$build/seeds/$t" -fork="$(nproc)" -ignore_crashes=1 \
    -ignore_timeouts=1 -ignore_ooms=1 -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 \
    -malloc_limit_mb=2048 -max_len="$max_len" -artifact_prefix="$build/findings/$t/" \
    >"$build/$t.log" 2>&1 || true
  tail -3 "$build/$t.log"
  found=$(find "$build/findings/$t" -type f | wc -l)
  echo "fuzz: $t: $found finding(s) in $build/findings/$t"
  [ "$found" = 0 ] || status=1
done
exit $status
