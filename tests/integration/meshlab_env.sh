# Sourced by the MeshLab tests: a private copy of Debian's MeshLab 2020.09 layout that
# loads the freshly built plugin, so that tests never touch the system plugin folder.
# Debian's MeshLab finds its plugins relative to its executable (bin/ ->
# ../lib/x86_64-linux-gnu/meshlab/plugins, Debian patch 22_find-plugins) and its
# libmeshlab-common through an $ORIGIN-relative RUNPATH: the copies get the same tree.
# Usage: ml_env_setup PLUGIN_SO; then ml_run meshlabserver|meshlab ARGS...
ml_env_setup() {
  local plugin=$1 system=/usr/lib/x86_64-linux-gnu/meshlab
  ML_ROOT=$(mktemp -d /tmp/qs_meshlab.XXXXXX)
  ML_BIN=$ML_ROOT/bin
  local lib=$ML_ROOT/lib/x86_64-linux-gnu/meshlab
  mkdir -p "$ML_BIN" "$lib/plugins"
  cp /usr/bin/meshlabserver /usr/bin/meshlab "$ML_BIN/"
  ln -s "$system/libmeshlab-common.so" "$lib/"
  for so in "$system"/plugins/*.so; do
    case "$(basename "$so")" in libfilter_quadsimp.so) continue ;; esac
    ln -s "$so" "$lib/plugins/"
  done
  ln -s "$(readlink -f "$plugin")" "$lib/plugins/libfilter_quadsimp.so"
  trap 'rm -rf "$ML_ROOT"' EXIT
}

ml_run() {
  local program=$1
  shift
  xvfb-run -a "$ML_BIN/$program" "$@"
}

# The shared bunny.ply if DATASETS has it, else glmark2's bunny written as PLY to OUT:
# Debian's MeshLab 2020.09 aborts on every OBJ (Debian bug #1054006). Prints the path.
# Usage: ml_bunny_ply DATASETS_DIR QUADSIMP_CLI OUT.ply
ml_bunny_ply() {
  local datasets=$1 cli=$2 out=$3
  if [ -f "$datasets/bunny.ply" ]; then
    echo "$datasets/bunny.ply"
  else
    "$cli" fitmap /usr/share/glmark2/models/bunny.obj "$out" -q >/dev/null && echo "$out"
  fi
}
