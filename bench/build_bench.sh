#!/bin/sh
# bench/build_bench.sh [WANGSCAPE...]: `wangscape build` of the default scene with all three
# exports on (POV-Ray, Blender arrays, glTF), RUNS times per binary, interleaved so that every
# binary sees the same load; prints the fastest wall and user time of each. Compare builds:
#   sh bench/build_bench.sh /tmp/wangscape-before build/release/cli/wangscape
set -eu
runs=${RUNS:-5}
[ $# -gt 0 ] || set -- build/release/cli/wangscape
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$1" demo --print-scene > "$work/scene.toml"
printf 'blender = true\ngltf = true\n' >> "$work/scene.toml"  # [exports] is the file's last table
i=0
while [ "$i" -lt "$runs" ]; do
  n=0
  for bin in "$@"; do
    n=$((n + 1))
    rm -rf "$work/out"
    /usr/bin/time -f "%e %U" -o "$work/time" "$bin" --quiet build "$work/scene.toml" --out "$work/out"
    cat "$work/time" >> "$work/times.$n"
  done
  i=$((i + 1))
done
n=0
for bin in "$@"; do
  n=$((n + 1))
  sort -n "$work/times.$n" | head -1 | awk -v b="$bin" -v r="$runs" '{printf "%s: fastest of %d: %.2f s wall, %.2f s user\n", b, r, $1, $2}'
done
flowers=$(grep -c '^object' "$work/out/instances.inc" || true)
echo "flowers: $flowers"
