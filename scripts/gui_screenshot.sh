#!/usr/bin/env bash
# Starts Debian's MeshLab 2020.09 under Xvfb with the plugin just built (a private copy
# of the MeshLab tree, as the tests use), opens Filters > Polygonal and Quad Mesh and
# then the Quad Mesh Simplification dialog, applies it, and saves screenshots:
#   docs/meshlab_filters_menu.png, docs/meshlab_simplification_dialog.png, docs/meshlab_result.png
# Needs the build (scripts/build.sh); installs xdotool and imagemagick if missing.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
plugin=$here/build/plugins/meshlab2020/libfilter_quadsimp.so
[ -f "$plugin" ] || { echo "gui_screenshot: build first (scripts/build.sh): $plugin is missing" >&2; exit 1; }
for tool in xdotool:xdotool import:imagemagick Xvfb:xvfb; do
  command -v "${tool%%:*}" >/dev/null || apt-get install -y -qq --no-install-recommends "${tool##*:}" >/dev/null
done
source "$here/tests/integration/meshlab_env.sh"
ml_env_setup "$plugin"
mesh=$(ml_bunny_ply "$here/../shared/datasets" "$here/build/src/quadsimp" "$ML_ROOT/bunny.ply")
display=:$((90 + RANDOM % 100))
Xvfb "$display" -screen 0 1280x1400x24 >/dev/null 2>&1 &  # tall enough for the whole dialog
xvfb=$!
export DISPLAY=$display
sleep 1
"$ML_BIN/meshlab" "$mesh" >"$ML_ROOT/meshlab.log" 2>&1 &
meshlab=$!
trap 'kill $meshlab $xvfb 2>/dev/null; rm -rf "$ML_ROOT"' EXIT
sleep 8

# Menu positions of MeshLab 2020.09's default layout at this screen size.
xdotool mousemove 120 10 click 1
sleep 1
xdotool mousemove 200 186 && sleep 0.3 && xdotool mousemove 210 187 click 1
sleep 1
import -window root -crop 853x725+0+0 "$here/docs/meshlab_filters_menu.png"
xdotool mousemove 560 211 && sleep 0.3 && xdotool mousemove 622 211 click 1
sleep 2
# The dialog whole, every parameter shown: its geometry grows with its parameters.
eval "$(xdotool search --name "Quad Mesh Simplification" getwindowgeometry --shell | tail -n 6)"
import -window root -crop "${WIDTH}x$((Y + HEIGHT))+0+0" "$here/docs/meshlab_simplification_dialog.png"
# Apply with the defaults, close the dialog, and show the new layer as a wireframe
# (MeshLab hides faux edges there, so the quads show). Apply and Close are the dialog's
# bottom row, right and left.
xdotool mousemove $((X + 3 * WIDTH / 4)) $((Y + HEIGHT - 18)) click 1   # Apply
sleep 6
xdotool mousemove $((X + WIDTH / 4)) $((Y + HEIGHT - 18)) click 1   # Close
sleep 1
xdotool mousemove 471 114 click 1   # hide the input layer
sleep 1
xdotool mousemove 380 46 click 1
sleep 1
xdotool mousemove 530 145 click 1   # select the result layer
sleep 1
xdotool mousemove 572 372 click 1   # its wireframe settings
sleep 2
import -window root -crop 853x725+0+0 "$here/docs/meshlab_result.png"
echo "screenshots in $here/docs: meshlab_filters_menu.png meshlab_simplification_dialog.png meshlab_result.png"
