#!/bin/sh
# bench/view_bench.sh [WANGSCAPE] [FOLDER] (the CLI side of build/release/bench/view_bench, the
# Google Benchmark of the same views with the phases and the reference): frames/s and depth pixels/s of the real-time LDI view
# (`wangscape view --stats`, median of REPEAT frames) on the default scene built with the LDI
# export, from four cameras (at the field's northern edge looking south across it: the scene's
# own camera; in the field; from above the field; 1.5 m from a flower) at 640x360 and 1280x720,
# with the near field at its default distance (NEAR=0: LDIs only), by each engine (ENGINES, default
# "auto ldi embree": the default choice, LDIs beyond the near field, the whole frame ray cast). FOLDER (default
# out/view-bench) is built once and reused. Prints the load before each figure.
set -eu
bin=${1:-build/release/cli/wangscape}
dir=${2:-out/view-bench}
repeat=${REPEAT:-100}
if [ ! -s "$dir/tiles.ldi" ]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  "$bin" demo --print-scene | sed 's/^povray = true$/povray = false\nldi = true/' > "$work/scene.toml"
  echo "building $dir (the default scene's LDI pack: 7 levels x 8 directions)"
  /usr/bin/time -f "build: %e s wall, %U s user" "$bin" --quiet build "$work/scene.toml" --out "$dir"
fi
"$bin" ldi info "$dir/tiles.ldi" | head -8
for size in 640x360 1280x720; do
  for camera in "edge (the scene's camera)|" "in the field|--camera 0,6300 --look-at 0,1200,1500" \
                "above the field|--camera 0,6640,1150 --look-at 0,6450,1125" \
                "close-up|--camera 1.0,6291.3,1131.6 --look-at -0.5,6291.3,1131.5"; do
    name=${camera%%|*}
    flags=${camera#*|}
    for engine in ${ENGINES:-auto ldi embree}; do
      echo "== $name, $size, --engine $engine; load: $(cut -d' ' -f1-3 /proc/loadavg)"
      # shellcheck disable=SC2086
      "$bin" --quiet view "$dir" $flags --size "$size" --near "${NEAR:-8}" --engine "$engine" --stats --repeat "$repeat"
    done
  done
done
