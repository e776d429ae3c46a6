#!/usr/bin/env bash
# The unit and CLI tests (qs_tests) under AddressSanitizer and UndefinedBehaviorSanitizer:
# builds build-asan/ (Debug at -O1, the CLI the tests run included) and runs the tests,
# which fail on the first report. 25 to 35 minutes on 2 cores, most of it the tests.
# Arguments go to the test binary (e.g. --gtest_filter='Simplify.*'). Needs
# scripts/setup.sh's packages only. The MeshLab plugins are not built.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$here/build-asan"
flags="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DQS_BUILD_PLUGIN_2020=OFF \
  -DQS_BUILD_PLUGIN_2025=OFF -DQS_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --target qs_tests quadsimp --parallel "$(nproc)"
cd "$build"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 tests/qs_tests --gtest_brief=1 "$@"
