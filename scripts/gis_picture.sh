#!/bin/sh
# docs/images/gis-plants.png: the plants of a build's plants.gpkg ([exports] gis) drawn over the DEM
# with GDAL's own programs, as a GIS would show them. The scene: a concave polygon with a hole on the
# pumice plain north of Mount St. Helens ([masks] polygons, WGS 84 GeoJSON), sown over its
# latitude/longitude box ([tiles] area_latlon). The picture is a 260 x 195 m corner of it at 0.325 m
# a pixel: the DEM's hillshade (resampled from its 30 m cells, cubic), each plant a yellow dot (a
# 0.25 m disc), the polygon's edge in red.
#   scripts/gis_picture.sh [WANGSCAPE] [OUT.png]
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
wangscape=${1:-$root/build/release/cli/wangscape}
out=${2:-$root/docs/images/gis-plants.png}
dem=$root/data/SainteHelens.dem
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

gdalsrsinfo -o wkt2 "$dem" > "$work/dem.wkt"
# The DEM's centre, 5.5 km north (the pumice plain), in the DEM's CRS.
set -- $(gdalinfo -json "$dem" | python3 -c '
import json, sys
d = json.load(sys.stdin)
t, (w, h) = d["geoTransform"], d["size"]
print(t[0] + w * t[1] / 2, t[3] + h * t[5] / 2 + 5500)')
cx=$1 cy=$2
# The polygon (as the tests' mask_polygons), in WGS 84.
ring() { for p in "$@"; do echo "$cx $cy ${p%,*} ${p#*,}" | awk '{printf "%.3f %.3f\n", $1 + $3, $2 + $4}'; done |
  gdaltransform -s_srs "$work/dem.wkt" -t_srs EPSG:4326 -output_xy | awk '{printf "%s[%s,%s]", (NR > 1 ? "," : ""), $1, $2}'; }
outer=$(ring -250,-250 250,-200 230,0 0,20 -20,260 -260,240 -250,-250)
hole=$(ring -100,-60 -60,-100 -20,-60 -60,-20 -100,-60)
cat > "$work/mask.geojson" <<EOF
{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
 "geometry": {"type": "Polygon", "coordinates": [[$outer], [$hole]]}}]}
EOF
box=$(ogrinfo -so -al "$work/mask.geojson" | sed -n 's/^Extent: (\(.*\), \(.*\)) - (\(.*\), \(.*\))$/\2 \1 \4 \3/p' |
  awk '{m = 0.0005; printf "[%.7f, %.7f, %.7f, %.7f]", $1 - m, $2 - m, $3 + m, $4 + m}')
cat > "$work/scene.toml" <<EOF
name = "GIS picture"
[terrain]
dem = "$dem"
[tiles]
set = "cohen8"
tile_size = 4.0
points_per_tile = 20
relaxation_rounds = 8
seed = 7
area_latlon = $box
[masks]
polygons = "mask.geojson"
[models]
variants = 1
triangle_budget = 800
[camera_aware]
enabled = false
[exports]
povray = false
gis = true
EOF
"$wangscape" --quiet build "$work/scene.toml" --out "$work/field"

# The window: the polygon's south-west corner and its hole. The DEM's whole metres resampled as
# floats, or the hillshade shows their steps as contours.
x0=$(echo "$cx" | awk '{print $1 - 265}') y0=$(echo "$cy" | awk '{print $1 - 265}')
x1=$(echo "$x0" | awk '{print $1 + 260}') y1=$(echo "$y0" | awk '{print $1 + 195}')
gdalwarp -q -r cubic -ot Float32 -tr 0.325 0.325 -te "$x0" "$y0" "$x1" "$y1" "$dem" "$work/dem.tif"
gdaldem hillshade -q -z 3 "$work/dem.tif" "$work/shade.tif"
gdal_translate -q -b 1 -b 1 -b 1 -scale 0 255 60 200 "$work/shade.tif" "$work/rgb.tif"
gdal_rasterize -q -b 1 -b 2 -b 3 -burn 255 -burn 215 -burn 0 -dialect SQLite \
  -sql "SELECT ST_Buffer(geom, 0.25) FROM plants" "$work/field/plants.gpkg" "$work/rgb.tif"
ogr2ogr -q -t_srs "$work/dem.wkt" "$work/mask_dem.gpkg" "$work/mask.geojson"
gdal_rasterize -q -b 1 -b 2 -b 3 -burn 220 -burn 30 -burn 30 -dialect SQLite \
  -sql "SELECT ST_Buffer(ST_Boundary(geom), 0.3) FROM mask" "$work/mask_dem.gpkg" "$work/rgb.tif"
gdal_translate -q -of PNG -co ZLEVEL=9 "$work/rgb.tif" "$out"
echo "wrote $out ($(ogrinfo -so -al "$work/field/plants.gpkg" | sed -n 's/^Feature Count: //p') plants in the layer)"
