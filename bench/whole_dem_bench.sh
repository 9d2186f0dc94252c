#!/bin/sh
# bench/whole_dem_bench.sh [WANGSCAPE]: camera-aware export of the whole St. Helens DEM below
# 1,200 m (templates/scenes/whole-dem.toml) against the demo's 400 x 600 m patch. For each far
# distance in FARS (meters; "default" = one pixel per 30 cm head): build wall time, tiles
# visible/placed/culled and flowers as models/proxies (the build's own counts), POV-Ray wall
# time and peak memory at WIDTHxHEIGHT. The placement's time should follow the visible tiles,
# not the 8.4 million tiles of the DEM. Note the load (uptime) with every figure.
#   sh bench/whole_dem_bench.sh                       # FARS="100 default 400", 640 x 360
#   RENDER=0 FARS="50 100 200 400 800" sh bench/whole_dem_bench.sh
set -eu
bin=${1:-build/release/cli/wangscape}
fars=${FARS:-100 default 400}
width=${WIDTH:-640}
height=${HEIGHT:-360}
render=${RENDER:-1}
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
uptime
sed "s#\"../../data/SainteHelens.dem\"#\"$src/data/SainteHelens.dem\"#; s/^width = .*/width = $width/; s/^height = .*/height = $height/" \
  "$src/templates/scenes/whole-dem.toml" > "$work/whole.toml"
run() {  # NAME SCENE
  rm -rf "$work/out"
  /usr/bin/time -f "%e %M" -o "$work/time" "$bin" build "$2" --out "$work/out" 2> "$work/log"
  counts=$(grep 'tiles:' "$work/log" | sed 's/^wangscape: //' || true)
  printf '%s: build %s s (peak %s KB); %s\n' "$1" "$(cut -d' ' -f1 "$work/time")" "$(cut -d' ' -f2 "$work/time")" "$counts"
  if [ "$render" = 1 ]; then
    (cd "$work/out" && /usr/bin/time -f "%e %M" -o "$work/ptime" povray scene.ini -D > povray.log 2>&1)
    printf '%s: POV-Ray %sx%s %s s, peak %s KB\n' "$1" "$width" "$height" "$(cut -d' ' -f1 "$work/ptime")" \
      "$(cut -d' ' -f2 "$work/ptime")"
  fi
}
for far in $fars; do
  if [ "$far" = default ]; then
    cp "$work/whole.toml" "$work/scene.toml"
  else
    sed "s/^proxy_triangles = /far = $far.0\nproxy_triangles = /" "$work/whole.toml" > "$work/scene.toml"
  fi
  run "whole DEM, far $far" "$work/scene.toml"
done
"$bin" demo --print-scene | sed "s/^width = .*/width = $width/; s/^height = .*/height = $height/" > "$work/demo.toml"
run "demo patch (no camera-aware)" "$work/demo.toml"
uptime
