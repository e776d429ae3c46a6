#!/usr/bin/env bash
# The fuzzers' seed corpus (tests/fuzz/make_seeds.py) holds the meshes it says: every
# seed, its header bytes taken off, loads in the format its first byte picks (the
# readers' seeds are in that format's folder), as the shape it is (a sphere of 140
# triangles, a 3x3 grid and a cube of quads; the textured ones with their texture), and
# every image seed is read as a texture, so that scripts/fuzz.sh starts from files the
# readers take rather than from noise.
# Usage: fuzz_seeds_test.sh REPO_DIR QUADSIMP_CLI
set -euo pipefail
repo=$1 cli=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 "$repo/tests/fuzz/make_seeds.py" "$work/seeds" >/dev/null
extensions=(ply obj off stl)
cp "$work/seeds/read_image_fuzzer/rgba.png" "$work/t.png"
count=0
for target_header in read_mesh_fuzzer:1 simplify_fuzzer:2; do
  target=${target_header%:*} header=${target_header#*:}
  for seed in $(find "$work/seeds/$target" -type f | sort); do
    format=$(head -c 1 "$seed" | od -An -tu1 | tr -d ' ')
    file="$work/mesh.${extensions[$((format % 4))]}"
    # The readers' seeds are in a folder per format, for a campaign per reader.
    [ "$target" = simplify_fuzzer ] || [ "$(basename "$(dirname "$seed")")" = "${extensions[$((format % 4))]}" ] \
      || { echo "FAIL: $seed is not in its format's folder"; exit 1; }
    tail -c +$((header + 1)) "$seed" > "$file"
    [[ $file != *.obj ]] || cp "$file" "$work/m.mtl"  # as fuzz_input.h's write_mesh() does
    rm -f "$work/quads_texture.png"
    log=$("$cli" convert "$file" "$work/quads.obj" 2>&1) || { echo "FAIL: $target/$(basename "$seed"): $log"; exit 1; }
    case $(basename "$seed") in
      sphere*) expect="140 triangles -> 70 quads" ;;
      grid*) expect="already pure quad, 9 quads" ;;
      cube*) expect="already pure quad, 6 quads" ;;
    esac
    # An STL file holds triangles only: its quads come back paired.
    [[ $file == *.stl && $expect == already* ]] && expect="-> ${expect#already pure quad, }"
    grep -qF -- "$expect" <<<"$log" || { echo "FAIL: $target/$(basename "$seed"): '$log' lacks '$expect'"; exit 1; }
    # The textured seeds' texture reaches the quads.
    [[ $seed != *_textured* || -f $work/quads_texture.png ]] \
      || { echo "FAIL: $target/$(basename "$seed"): no texture baked: $log"; exit 1; }
    count=$((count + 1))
  done
done
[ "$count" = $((27 + 81)) ] || { echo "FAIL: $count seeds, expected 108"; exit 1; }
# Each image seed is read as the texture of a textured square (named without its
# extension: the reader goes by the file's first bytes).
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n' > "$work/tex.obj"
printf 'mtllib tex.mtl\nusemtl t\nf 1/1 2/2 3/3 4/4\n' >> "$work/tex.obj"
printf 'newmtl t\nmap_Kd image\n' > "$work/tex.mtl"
images=0
for seed in "$work/seeds/read_image_fuzzer"/*; do
  cp "$seed" "$work/image"
  rm -f "$work/square_texture.png"
  log=$("$cli" convert "$work/tex.obj" "$work/square.obj" 2>&1) || { echo "FAIL: $(basename "$seed"): $log"; exit 1; }
  [ -f "$work/square_texture.png" ] || { echo "FAIL: $(basename "$seed") not read as an image: $log"; exit 1; }
  images=$((images + 1))
done
[ "$images" = 14 ] || { echo "FAIL: $images image seeds, expected 14"; exit 1; }
echo "fuzz seeds: $count load as their shapes, $images images as textures"
