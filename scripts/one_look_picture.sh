#!/bin/sh
# docs/images/one-look.png: one camera, three engines (issue 39, "one look"). The default scene (or
# SCENE) from its own camera at 320 x 180 in POV-Ray, Blender Cycles and the Embree reference, side
# by side in that order, through bench/band_colors.py (which builds it with both exports and prints the
# band table of the three pictures: the figures belong with the picture).
#   scripts/one_look_picture.sh [WANGSCAPE] [OUT.png] [SCENE.toml]
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
wangscape=${1:-$root/build/release/cli/wangscape}
out=${2:-$root/docs/images/one-look.png}
scene=${3:-$root/templates/scenes/default.toml}
name=$(basename "$scene" .toml)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

/usr/bin/python3 "$root/bench/band_colors.py" table --wangscape "$wangscape" --out "$work" --width 320 --height 180 \
  "$scene" || true  # the table is printed either way; the picture shows what it measured
oiiotool "$work/${name}_povray.png" --ch R,G,B "$work/${name}_blender.png" --ch R,G,B \
  "$work/${name}_embree.png" --ch R,G,B --mosaic:pad=4 3x1 -d uint8 -o "$out"
echo "wrote $out ($(wc -c < "$out") bytes)"
