#!/usr/bin/env bash
# Installs everything quadsimp needs on a fresh Debian 12 machine (run as root).
# Idempotent: a second run only checks what is already there.
#
#   scripts/setup.sh            packages + MeshLab source tarballs into .deps/
#   QS_SKIP_MESHLAB_SRC=1 ...   packages only
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deps="${QS_DEPS_DIR:-$here/.deps}"

die() { echo "setup: $*" >&2; exit 1; }

[ "$(id -u)" = 0 ] || die "run as root (it installs Debian packages)."
command -v apt-get >/dev/null || die "this script needs Debian's apt-get (Debian 12 bookworm)."

packages=(
  build-essential cmake pkg-config ninja-build
  libembree-dev libeigen3-dev libtbb-dev libcli11-dev libboost-graph-dev libstb-dev libpng-dev libturbojpeg0-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  qtbase5-dev libqt5opengl5-dev libqt5xmlpatterns5-dev qtscript5-dev libglew-dev
  meshlab xvfb xauth glmark2-data
  python3 python3-venv python3-pip dpkg-dev patch
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq || die "apt-get update failed: is a Debian mirror reachable?"
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null \
    || die "apt-get could not install: ${missing[*]}"
fi

[ -f /usr/share/glmark2/models/bunny.obj ] || die "glmark2-data is installed but bunny.obj is missing."

# A venv with pymeshlab 2025.7 (PyPI): the MeshLab 2025.07 plugin links against the
# libmeshlab-common.so inside its wheel, and the Python tests run in it.
venv="${QS_VENV_DIR:-$here/.venv}"
# (One Python call: "pip show | grep -q" under pipefail failed whenever grep closed the
# pipe before pip had finished writing, and the venv was rebuilt on every run.)
if ! "$venv/bin/python" -c "import importlib.metadata as md, pymeshlab, pytest, sys
sys.exit(md.version('pymeshlab') != '2025.7')" 2>/dev/null; then
  echo "setup: creating $venv with pymeshlab==2025.7"
  python3 -m venv "$venv" || die "could not create the Python venv $venv (python3-venv)."
  "$venv/bin/python" -m pip install -q --disable-pip-version-check "pymeshlab==2025.7" pytest \
    || die "pip could not install pymeshlab==2025.7 and pytest from PyPI into $venv."
fi

[ "${QS_SKIP_MESHLAB_SRC:-0}" = 1 ] && { echo "setup: done (packages only)"; exit 0; }

# MeshLab source trees: headers of both plugin API generations, and vcglib for I/O.
# They come from Debian's source packages; each tarball is pinned by sha256 so that a
# changed archive is noticed instead of built.
src_list=/etc/apt/sources.list.d/quadsimp-meshlab-src.sources
if [ ! -f "$src_list" ]; then
  cat > "$src_list" <<'SRC'
# Added by quadsimp's scripts/setup.sh: source packages only (apt-get source meshlab/...).
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm sid
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  apt-get update -qq || die "apt-get update failed after adding the deb-src entry $src_list."
fi

fetch() {  # suite tarball sha256 folder-name
  local suite=$1 tarball=$2 sum=$3 name=$4
  [ -f "$deps/$name/.complete" ] && return 0
  mkdir -p "$deps/download"
  if [ ! -f "$deps/download/$tarball" ]; then
    (cd "$deps/download" && apt-get source --tar-only "meshlab/$suite" >/dev/null 2>&1) \
      || die "could not download the MeshLab source package meshlab/$suite (apt-get source --tar-only)."
    [ -f "$deps/download/$tarball" ] || die "meshlab/$suite did not provide $tarball (has Debian moved to a new version?)."
  fi
  echo "$sum  $deps/download/$tarball" | sha256sum -c --quiet - \
    || die "$tarball does not have the expected sha256 $sum."
  rm -rf "$deps/$name.tmp" && mkdir -p "$deps/$name.tmp"
  tar -xf "$deps/download/$tarball" -C "$deps/$name.tmp" --strip-components=1
  rm -rf "$deps/$name" && mv "$deps/$name.tmp" "$deps/$name"
  touch "$deps/$name/.complete"
  echo "setup: unpacked $tarball into $deps/$name"
}

fetch bookworm "meshlab_2020.09+dfsg1.orig.tar.xz" \
  d6715352ff65caffdec0292858d4263eb0c3cbbf3b1e5c2e2bab218e3f234630 meshlab-2020.09
fetch sid "meshlab_2025.07~dfsg.orig.tar.xz" \
  d22c98d362f2a284e481af8dbfc272b2222f5b9c67b3cf8bec57d1c3161886f4 meshlab-2025.07
rm -rf "$deps/download"

# Fixes of ours to vcglib's readers (each patch says what it mends), applied once.
for p in "$here"/scripts/patches/*.patch; do
  [ -f "$p" ] || continue
  patch -d "$deps/meshlab-2025.07" -p1 -R -s -f --dry-run < "$p" >/dev/null 2>&1 && continue  # applied already
  patch -d "$deps/meshlab-2025.07" -p1 -s -f --dry-run < "$p" >/dev/null 2>&1 \
    || die "$p applies neither way to $deps/meshlab-2025.07 (partly applied?): remove that folder and run setup again."
  patch -d "$deps/meshlab-2025.07" -p1 -s < "$p" >/dev/null || die "could not apply $p to $deps/meshlab-2025.07."
  echo "setup: applied $(basename "$p")"
done
echo "setup: done"
