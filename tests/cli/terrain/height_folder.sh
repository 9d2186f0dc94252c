#!/bin/sh
# height_folder.sh BIN SCRATCH DEM SRC: `terrain height` of a scene file and of the folder built from
# it reads their [terrain]: with the origin moved to the DEM's point (0, 6590), the point 0,0 of
# the scene is that ground (1117.89 m), as the scene's camera and a view path see it.
set -eu
BIN=$1
DIR=$2
DEM=$3
SRC=$4
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$DIR"
mkdir -p "$DIR"
cd "$DIR"
# templates/scenes/small.toml with its origin moved and its field and camera moved with it.
sed -e "s#^dem = .*#dem = \"$DEM\"#" \
    -e 's#^\[terrain\]$#[terrain]\norigin_latitude = 46.24659967532685\norigin_longitude = -122.18859025851513#' \
    -e 's#^area = .*#area = [-8.0, -8.0, 8.0, 8.0]#' -e 's#^position = .*#position = [0.0, 10.0]#' \
    -e 's#^target = .*#target = [0.0, -20.0, 1117.0]#' -e 's#^ldi = true.*#ldi = false#' \
    "$SRC/templates/scenes/small.toml" > scene.toml
dem_says=$("$BIN" terrain height "$DEM" 0,6590) || fail "terrain height DEM"
[ "$dem_says" = "0.00,6590.00,1117.89" ] || fail "DEM: $dem_says"
file_says=$("$BIN" terrain height scene.toml 0,0) || fail "terrain height scene.toml"
[ "$file_says" = "0.00,0.00,1117.89" ] || fail "scene file: $file_says"
"$BIN" -q build scene.toml --out field || fail "build"
folder_says=$("$BIN" terrain height field 0,0 --above 1.7) || fail "terrain height field"
[ "$folder_says" = "0.00,0.00,1119.59" ] || fail "folder: $folder_says"
# The scene sets its origin: --origin is refused (a usage of the DEM only).
if "$BIN" terrain height field 0,0 --origin 46.2,-122.2 2> err.txt; then fail "--origin with a folder accepted"; fi
grep -q "the scene's \[terrain\] sets the origin" err.txt || fail "message: $(cat err.txt)"
echo ok
