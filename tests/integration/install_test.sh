#!/usr/bin/env bash
# `cmake --install` puts the MeshLab 2020.09 plugin where Debian's MeshLab loads it
# (staged with DESTDIR, so the test does not touch the system), and the folder can be
# changed with QS_PLUGIN_2020_INSTALL_DIR.
# Usage: install_test.sh BUILD_DIR
set -euo pipefail
build=$1
stage=$(mktemp -d /tmp/qs_install.XXXXXX)
trap 'rm -rf "$stage"' EXIT
DESTDIR=$stage cmake --install "$build" >/dev/null
plugin=$stage/usr/lib/x86_64-linux-gnu/meshlab/plugins/libfilter_quadsimp.so
[ -f "$plugin" ] || { echo "FAIL: $plugin not installed"; find "$stage" -type f; exit 1; }
[ -x "$stage/usr/local/bin/quadsimp" ] || { echo "FAIL: quadsimp not installed in bin/"; exit 1; }
echo "ok: $plugin"
