#!/usr/bin/env bash
# Installs the Python package (with the plugin just built) into the project's venv,
# the way the README shows, and runs the pymeshlab tests there.
# Usage: run_tests.sh VENV_DIR REPO_DIR PLUGIN_SO QUADSIMP_CLI
set -euo pipefail
venv=$1 repo=$2 plugin=$3 cli=$4
QUADSIMP_PLUGIN=$plugin "$venv/bin/python" -m pip install -q --disable-pip-version-check --no-deps \
  --force-reinstall "$repo/python"
unset QUADSIMP_PLUGIN  # the tests load the copy the package bundles
cd "$repo/tests/python"
QUADSIMP_CLI=$cli exec "$venv/bin/python" -m pytest -q -p no:cacheprovider .
