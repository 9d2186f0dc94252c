#!/bin/sh
# bench/scatter_stream_bench.sh [WANGSCAPE]: `scatter --dem` streams its points (issue 24): over a
# synthetic DEM of 25 x 27 km at 30 m (834 x 900 samples, WGS 84 / UTM 10N, hills from about 300
# to 2,300 m; made with python3-gdal into a temporary folder, never committed), 4 m tiles of a
# cohen8 set filled with 20 points (844 million points before the masks), below MAX_HEIGHT.
# Prints the command, the load, the points written, points/s, peak memory (/usr/bin/time -v)
# and the file's size; the points file is removed at the end.
#   sh bench/scatter_stream_bench.sh                        # PLY, below 1,200 m
#   FORMAT=csv MAX_HEIGHT=900 sh bench/scatter_stream_bench.sh
#   WORK=/big/disk sh bench/scatter_stream_bench.sh          # where the DEM and the points go
set -eu
bin=$(realpath "${1:-build/release/cli/wangscape}")
format=${FORMAT:-ply}
max_height=${MAX_HEIGHT:-1200}
work=$(mktemp -d "${WORK:-${TMPDIR:-/tmp}}/scatter-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3  # Debian's python3 has GDAL's bindings and numpy

"$PY" - "$work/dem.tif" <<'PY'
import sys
import numpy as np
from osgeo import gdal, osr
w, h, step = 834, 900, 30.0                 # 25.02 x 27.0 km
x0, y0 = 550000.0, 5125000.0                # the north-west corner, near St. Helens
x = np.arange(w) * step
y = np.arange(h)[:, None] * step
z = 600 + 1400 * (y / (h * step)) + 300 * np.sin(x / 2000.0) * np.cos(y / 1500.0)
ds = gdal.GetDriverByName("GTiff").Create(sys.argv[1], w, h, 1, gdal.GDT_Float32, ["COMPRESS=DEFLATE"])
ds.SetGeoTransform((x0, step, 0, y0, 0, -step))
srs = osr.SpatialReference()
srs.ImportFromEPSG(32610)
ds.SetProjection(srs.ExportToWkt())
ds.GetRasterBand(1).WriteArray(z.astype(np.float32))
ds = None
PY
"$bin" -q tileset --set cohen8 --per-tile 20 --out "$work/tiles.json" > /dev/null
"$bin" terrain info "$work/dem.tif" | grep -E "size|spacing|heights"
cmd="$bin scatter --tileset tiles.json --dem dem.tif --tile-size 4 --max-height $max_height --out points.$format --yes"
echo "command: (in $work) $cmd"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
(cd "$work" && /usr/bin/time -v -o time.txt $cmd 2> said.txt) || { cat "$work/said.txt" "$work/time.txt"; exit 1; }
echo "load after:  $(cut -d' ' -f1-3 /proc/loadavg)"
cat "$work/said.txt"
points=$(sed -n 's/^wangscape: wrote [^ ]* (\([0-9]*\) instances.*/\1/p' "$work/said.txt")
wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$work/time.txt" |
  awk -F: '{ s = 0; for (i = 1; i <= NF; ++i) s = s * 60 + $i; print s }')
peak=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$work/time.txt")
user=$(sed -n 's/.*User time (seconds): //p' "$work/time.txt")
bytes=$(stat -c %s "$work/points.$format")
awk -v p="$points" -v w="$wall" -v u="$user" -v k="$peak" -v b="$bytes" 'BEGIN {
  printf "points: %d in %.1f s wall (%.1f s user): %.2f million points/s; peak memory %.0f MB; file %.2f GB\n",
    p, w, u, p / w / 1e6, k / 1024, b / 1e9 }'
