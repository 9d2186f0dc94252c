#!/bin/sh
# The Embree reference against POV-Ray on the same still (issue 11): the default scene (Mount St.
# Helens, its own camera and size, 640x360) built once, then rendered from the folder by both
# engines, end to end (Embree: scene assembly, placement, BVH build, tracing; POV-Ray: parse and
# trace). Wall clock of each, best of REPEAT runs, with the load beside it.
# Measured on the shared 2-core machine at a load of ~11: Embree 14.7 s end to end (of which
# render_reference 8.7 s: 2.1 s placement + BVH build, 6.6 s tracing 4 spp), POV-Ray 40.8 s.
# Usage: bench/embree_vs_povray_bench.sh [path/to/wangscape] [scratch dir] [repeat]
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/release/cli/wangscape}
scratch=${2:-${TMPDIR:-/tmp}/wangscape_embree_bench}
repeat=${3:-1}
mkdir -p "$scratch"
"$bin" demo --print-scene > "$scratch/default.toml"
rm -rf "$scratch/default"
"$bin" --quiet build "$scratch/default.toml" --out "$scratch/default"
now() { date +%s.%N; }
best() {  # best ENGINE: the shortest wall time of `repeat` renders, in seconds
  b=""
  i=0
  while [ "$i" -lt "$repeat" ]; do
    t0=$(now)
    "$bin" --quiet render "$scratch/default" --engine "$1"
    t1=$(now)
    b=$(awk -v a="$t0" -v z="$t1" -v b="$b" 'BEGIN { t = z - a; if (b == "" || t < b) b = t; print b }')
    i=$((i + 1))
  done
  awk -v b="$b" 'BEGIN { printf "%.2f", b }'
}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
embree=$(best embree)
echo "load after Embree: $(cut -d' ' -f1-3 /proc/loadavg)"
povray=$(best povray)
echo "load after POV-Ray: $(cut -d' ' -f1-3 /proc/loadavg)"
instances=$(grep -c "^object" "$scratch/default/instances.inc")
echo "default scene, $instances flowers, 640x360: Embree reference ${embree} s, POV-Ray ${povray} s" \
     "(POV-Ray / Embree = $(awk -v p="$povray" -v e="$embree" 'BEGIN { printf "%.1f", p / e }'))"
echo "images: $scratch/default/render_embree.png $scratch/default/render.png"
