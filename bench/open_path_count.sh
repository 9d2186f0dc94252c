#!/usr/bin/env bash
# Counts the files the viewer's path visits when it opens a scene folder, and the climbs back,
# from a run of an instrumented wangscape (method: bench/open_path/README.md).
#
#   bench/open_path_count.sh [FOLDER] [--list]
#
# FOLDER: a scene folder built with [exports] ldi (default /tmp/open_path_field, built from the
# demo scene with ldi on when missing, about a minute). --list also prints the files and climbs.
# The instrumented build lives in build/open-path (its own directory; one job).
set -euo pipefail
cd "$(dirname "$0")/.."
src=$PWD
bdir=$src/build/open-path
folder=${1:-/tmp/open_path_field}
list=${2:-}

# ---- the instrumented binary: project code only (every header under /usr/ left out) ----
mkdir -p "$bdir"
hook=$bdir/trace_hook.o
if [[ ! -f $hook || $src/bench/open_path/trace_hook.c -nt $hook ]]; then
  cc -O2 -fPIC -c "$src/bench/open_path/trace_hook.c" -o "$hook"
fi
if [[ ! -f $bdir/build.ninja ]]; then
  cmake -S "$src" -B "$bdir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_FLAGS="-finstrument-functions -finstrument-functions-exclude-file-list=/usr/" \
    -DCMAKE_EXE_LINKER_FLAGS="$hook -pthread" \
    -DWANGSCAPE_BUILD_TESTS=OFF -DWANGSCAPE_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$bdir" -j1 --target wangscape >/dev/null
bin=$bdir/cli/wangscape

# ---- the folder: the demo scene with its LDI pack ----
if [[ ! -f $folder/tiles.ldi ]]; then
  "$bin" demo --print-scene | sed 's/^ldi = false /ldi = true  /' >"$folder.toml"
  "$src/build/release/cli/wangscape" build "$folder.toml" --out "$folder" >/dev/null 2>&1 ||
    "$bin" build "$folder.toml" --out "$folder" >/dev/null
fi

# ---- two windows: ViewWorld::load's own calls; from ViewWorld::load to the first frame ----
symbol() { nm -C "$bin" | awk -v s="$1" 'index($0, s) && !n++ { print $1 }'; }
base=$(nm "$bin" | awk '$3 == "__executable_start" { print $1 }')
root=$(symbol " wangscape::ViewWorld::load(")
stop=$(symbol " wangscape::LdiRenderer::render(")
off() { printf '%x' $((0x$1 - 0x$base)); }
out=$bdir/trace
OPEN_PATH_ROOT=$(off "$root") OPEN_PATH_OUT=$out.load \
  "$bin" --quiet view "$folder" --out "$bdir/frame.png" --size 16x9 --threads 1
OPEN_PATH_ROOT=$(off "$root") OPEN_PATH_STOP=$(off "$stop") OPEN_PATH_OUT=$out.first_frame \
  "$bin" --quiet view "$folder" --out "$bdir/frame.png" --size 16x9 --threads 1
python3 "$src/bench/open_path/count.py" "$bin" "$base" "$src" "$out.load" "$out.first_frame" $list
