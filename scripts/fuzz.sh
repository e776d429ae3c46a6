#!/usr/bin/env bash
# Coverage-guided fuzzing (libFuzzer, with AddressSanitizer and UndefinedBehaviorSanitizer)
# of the mesh readers, the texture images' reader and the whole run on small meshes
# (tests/fuzz/): builds build-fuzz/ with clang, writes a seed corpus of small files in
# every format, and runs six campaigns of SECONDS each (default 300) on all cores: one per
# mesh reader (PLY, OBJ, OFF, STL: in one campaign for all four, the small readers' files
# were too few of the corpus to be mutated much), one for images, then the whole run.
# libpng and libjpeg-turbo, Debian's builds, are not instrumented, so their inputs are
# mutated blind (OSS-Fuzz fuzzes them upstream); our code and stb's decoders guide it.
# Inputs that crash, hang (over 20 s), allocate over 2 GB, break a promise (fuzz_input.h's
# require()) or throw anything but a refusal go to build-fuzz/findings/CAMPAIGN/, and a
# fuzzer that stops before its time is reported with its log's end; replay a finding
# with `build-fuzz/tests/fuzz/TARGET FILE`.
# The corpora grow in build-fuzz/corpus/CAMPAIGN/ and a later run goes on from them; the
# fuzzers' logs are in build-fuzz/logs/CAMPAIGN/. Needs scripts/setup.sh's packages, and
# Debian's clang and its runtime libraries (libFuzzer), which it installs when missing.
#
#   scripts/fuzz.sh [SECONDS] [CAMPAIGN...]    CAMPAIGN: ply obj off stl image simplify
#   scripts/fuzz.sh --smoke
#
# --smoke is the suite's short run (ctest's fuzz_smoke, about four minutes on 2 cores):
# every campaign once, one fuzzer each, from the seeds alone (a fresh corpus, not
# build-fuzz/corpus/), for a fixed number of inputs: 100,000 for a reader, 2,000 for the
# whole run. It cannot replace the campaigns, but a change that breaks a reader on its
# seeds' near neighbours fails the suite. Two runs are not the same inputs (one seed gave
# two coverages): a finding is kept in build-fuzz/smoke-findings/ to replay. Exits 77
# (skipped) where clang is missing and cannot be installed.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$here/build-fuzz"
smoke=0
[ "${1:-}" != --smoke ] || { smoke=1; shift; }
seconds=300
[ $smoke = 1 ] || { seconds=${1:-300}; shift || true; }
campaigns=("$@")
[ ${#campaigns[@]} -gt 0 ] || campaigns=(ply obj off stl image simplify)
runtime() { clang++ -print-file-name=libclang_rt.fuzzer-x86_64.a; }
if ! command -v clang++ >/dev/null || [ ! -f "$(runtime)" ]; then  # libFuzzer: Debian's clang runtime
  if [ "$(id -u)" != 0 ]; then
    echo "fuzz: clang++ or libFuzzer not found; as root: apt-get install clang libclang-rt-dev" >&2
    exit $((smoke ? 77 : 1))
  fi
  echo "fuzz: installing Debian's clang and its runtime (libFuzzer)"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -qq --no-install-recommends clang libclang-rt-dev >/dev/null 2>&1 \
    || { apt-get update -qq && apt-get install -y -qq --no-install-recommends clang libclang-rt-dev >/dev/null; }
fi

flags="-O1 -g -fsanitize=address,undefined,fuzzer-no-link -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DQS_BUILD_FUZZERS=ON -DQS_BUILD_TESTS=OFF \
  -DQS_BUILD_BENCH=OFF -DQS_BUILD_CLI=OFF -DQS_BUILD_PLUGIN_2020=OFF -DQS_BUILD_PLUGIN_2025=OFF >/dev/null
cmake --build "$build" --target read_mesh_fuzzer read_image_fuzzer simplify_fuzzer --parallel "$(nproc)"
python3 "$here/tests/fuzz/make_seeds.py" "$build/seeds"

status=0
for c in "${campaigns[@]}"; do
  case $c in
    ply | obj | off | stl) target=read_mesh_fuzzer seeds="$build/seeds/read_mesh_fuzzer/$c" max_len=65536 ;;
    image) target=read_image_fuzzer seeds="$build/seeds/read_image_fuzzer" max_len=65536 ;;
    # The whole run's meshes stay small: a few hundred triangles at most.
    simplify) target=simplify_fuzzer seeds="$build/seeds/simplify_fuzzer" max_len=16384 ;;
    *) echo "fuzz: unknown campaign '$c' (ply, obj, off, stl, image or simplify)" >&2; exit 2 ;;
  esac
  dict=()  # the mesh formats' keywords
  [ "$c" = image ] || dict=(-dict="$here/tests/fuzz/mesh.dict")
  limits=(-rss_limit_mb=4096 -malloc_limit_mb=2048 -max_len="$max_len" -use_value_profile=1)
  if [ $smoke = 1 ]; then
    runs=100000
    [ "$c" != simplify ] || runs=2000
    findings="$build/smoke-findings/$c"
    rm -rf "$findings" "$build/smoke-corpus/$c"
    mkdir -p "$findings" "$build/smoke-corpus/$c"
    echo "fuzz: $c ($target), $runs inputs from the seeds"
    log="$build/smoke-findings/$c.log"
    # A hang is still one at 120 s; 20 s could be one slow input on a machine as busy as
    # the suite makes it (its builds and tests beside this).
    ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 "$build/tests/fuzz/$target" \
      "$build/smoke-corpus/$c" "$seeds" -seed=1 -runs="$runs" -timeout=120 "${limits[@]}" "${dict[@]}" \
      -artifact_prefix="$findings/" >"$log" 2>&1 || true
    grep -E '^#[0-9]+' "$log" | tail -1
    found=$(find "$findings" -type f | wc -l)
    if [ "$found" != 0 ] || ! grep -qE '^#[0-9]+[[:space:]]+DONE' "$log"; then
      echo "fuzz: $c: $found finding(s), replay with: $build/tests/fuzz/$target FILE"
      find "$findings" -type f
      tail -40 "$log"
      status=1
    else
      rm -rf "$build/smoke-corpus/$c"
    fi
    continue
  fi
  mkdir -p "$build/corpus/$c" "$build/findings/$c" "$build/logs/$c"
  rm -f "$build/logs/$c"/fuzz-*.log  # an earlier run's, on more cores, would be read as this one's
  echo "fuzz: $c ($target) for $seconds s"
  # One fuzzer per core sharing the corpus (each stops at its first finding). Not -fork:
  # its short jobs lost the comparisons' guidance (-use_value_profile) that leads to the
  # edges of the readers' checks, a corner equal to the vertex count: a planted
  # off-by-one there was found by both of two single fuzzers (after 3,000 and 56,000
  # runs), and not in 222,000 runs of -fork.
  (cd "$build/logs/$c" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/tests/fuzz/$target" "$build/corpus/$c" "$seeds" -jobs="$(nproc)" -workers="$(nproc)" \
    -max_total_time="$seconds" -timeout=20 "${limits[@]}" "${dict[@]}" -artifact_prefix="$build/findings/$c/" \
    >/dev/null 2>&1) || true
  for log in "$build/logs/$c"/fuzz-*.log; do
    grep -E '^#[0-9]+' "$log" | tail -1
    # A fuzzer that did not run its time out met something: a finding, or a failure of
    # its own that wrote none ("Too many open files" was vcglib's STL reader leaking them).
    grep -qE '^#[0-9]+[[:space:]]+DONE' "$log" || { echo "fuzz: $log ended early:"; tail -5 "$log"; status=1; }
  done
  found=$(find "$build/findings/$c" -type f | wc -l)
  echo "fuzz: $c: $found finding(s) in $build/findings/$c"
  [ "$found" = 0 ] || status=1
done
exit $status
