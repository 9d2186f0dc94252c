#!/usr/bin/env bash
# outputs_snapshot.sh WANGSCAPE OUT: the outputs a restructuring must leave byte for byte the same,
# made by one wangscape binary into OUT: the default scene's folder (POV-Ray files, LDI pack),
# view frames from four cameras at two sizes, an Embree reference still, a tiling, a tile set's
# sheet, and the whole-DEM template's folder (camera-aware export, the far field in the bake).
# Compare two snapshots with `diff -r OUT_A OUT_B` (bench/README.md). Run from the repository.
set -euo pipefail
bin=$(realpath "$1")
out=$2
rm -rf "$out"
mkdir -p "$out"
"$bin" demo --print-scene | sed 's/^\[exports\]$/[exports]\nldi = true/' > "$out/scene.toml"
"$bin" --quiet build "$out/scene.toml" --out "$out/field"
rm -f "$out/field/scene_base.txt"  # names the snapshot's own folder
for size in 640x360 1280x720; do
  "$bin" --quiet view "$out/field" --size $size --out "$out/frame-scene-$size.png"
  "$bin" --quiet view "$out/field" --size $size --camera 0,6300 --look-at 0,1200,1500 --out "$out/frame-field-$size.png"
  "$bin" --quiet view "$out/field" --size $size --camera 0,6640,1150 --look-at 0,6450,1125 --out "$out/frame-above-$size.png"
done
"$bin" --quiet render "$out/field" --engine embree --width 160 --height 90 --spp 2 --out "$out/embree.png"
"$bin" --quiet tiling --set cohen8 --size 32x32 --seed 3 --out "$out/tiling.png"
"$bin" --quiet tileset --set cohen8 --per-tile 20 --relax 20 --seed 1 --out "$out/tiles.json" --sheet "$out/sheet.png"
"$bin" --quiet build templates/scenes/whole-dem.toml --out "$out/whole-dem"
rm -f "$out/whole-dem/scene_base.txt"
# Paths that name the snapshot's folder or the checkout: the same text in every snapshot.
root=$(pwd)
for f in "$out"/scene.toml "$out"/*/scene.toml "$out"/*/scene.ini; do
  sed -i "s#$(realpath "$out")#OUT#g; s#$root#REPO#g" "$f"
done
echo "snapshot: $out"
