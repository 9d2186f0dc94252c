#!/bin/sh
# POV-Ray's own cost for big fields: parse + render time and peak memory (GNU time -v) for
# 100 k and 1 M sunflowers (400-triangle mesh2 variants, flat ground) at 320x240.
# Usage: bench/povray_render_bench.sh [path/to/wangscape] [scratch dir]
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/release/cli/wangscape}
scratch=${2:-${TMPDIR:-/tmp}/wangscape_povray_render_bench}
mkdir -p "$scratch"
# 20 flowers per 4 m tile: 100 k flowers on 80 000 m^2 (283 m square), 1 M on 894 m square.
for spec in "100k 141.4" "1M 447.2"; do
  set -- $spec
  name=$1 half=$2
  cat > "$scratch/$name.toml" <<EOT
name = "povray bench $name"
[terrain]
flat_size = 1000.0
[tiles]
tile_size = 4.0
points_per_tile = 20
area = [-$half, -$half, $half, $half]
[models]
variants = 11
triangle_budget = 400
[camera]
position = [0.0, -$half, 2.5]
target = [0.0, 0.0, 1.0]
[image]
width = 320
height = 240
antialias = 1
EOT
  rm -rf "$scratch/$name"
  "$bin" --quiet build "$scratch/$name.toml" --out "$scratch/$name"
  instances=$(head -1 "$scratch/$name/instances.inc" | cut -d' ' -f2)
  size=$(du -m "$scratch/$name/instances.inc" | cut -f1)
  (cd "$scratch/$name" && /usr/bin/time -v povray scene.ini +W320 +H240 -D +Obench.png > time.log 2>&1) || {
    tail -20 "$scratch/$name/time.log"; exit 1; }
  elapsed=$(grep "Elapsed (wall clock)" "$scratch/$name/time.log" | sed 's/.*: //')
  rss=$(grep "Maximum resident" "$scratch/$name/time.log" | sed 's/.*: //')
  parse=$(grep -m1 "Parse Time:" "$scratch/$name/time.log" | sed 's/.*(\(.*\) seconds).*/\1/')
  trace=$(grep -m1 "Trace Time:" "$scratch/$name/time.log" | sed 's/.*(\(.*\) seconds).*/\1/')
  echo "$name: $instances instances ($size MB instances.inc): POV-Ray wall $elapsed, parse ${parse}s, trace ${trace}s, peak RSS $((rss / 1024)) MB"
done
