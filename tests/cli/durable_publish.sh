#!/bin/sh
# durable_publish.sh WANGSCAPE DIR CHECKER: issue 41's durable publishing, seen from the system
# calls. Runs under strace, in DIR (emptied first): a build of a tiny scene with every export
# (POV-Ray, Blender, glTF, the LDI pack, scene.cache) into a new folder and again over it (the
# swap), a filled tile set and a scatter of it, and a one-still batch (POV-Ray). Then
# durable_check.py (CHECKER) reads the trace: every published file synced before its rename,
# every folder synced after the renames into it, the parent after each publishing rename.
# Exit 77 (skipped) when this machine refuses ptrace; a missing strace is a failure (it is in
# scripts/debian-packages.txt).
set -u
bin=$1
dir=$2
checker=$3
fail() {
  echo "durable_publish: $*" >&2
  exit 1
}
command -v strace >/dev/null || fail "no strace: install it (scripts/debian-packages.txt)"
strace -o /dev/null true 2>/dev/null || {
  echo "durable_publish: skipped: strace cannot trace here (ptrace refused)"
  exit 77
}
case $bin in /*) ;; */*) bin=$(pwd)/$bin ;; esac
case $checker in /*) ;; *) checker=$(pwd)/$checker ;; esac
rm -rf "$dir"
mkdir -p "$dir" || fail "cannot create $dir"
cd "$dir" || exit 1
dir=$(pwd -P)

cat >scene.toml <<'EOF'
name = "durable"
[terrain]
flat_size = 60.0
[tiles]
set = "cohen8"
tile_size = 4.0
points_per_tile = 6
seed = 5
area = [-8.0, -8.0, 8.0, 8.0]
[models]
variants = 2
triangle_budget = 400
[camera]
position = [0.0, -12.0, 2.2]
target = [0.0, 0.0, 1.2]
[sun]
azimuth = 200.0
elevation = 40.0
[image]
width = 48
height = 36
[exports]
povray = true
blender = true
gltf = true
ldi = true
[ldi]
levels = 1
directions = 2
sky_rays = 0
EOF
cat >one.toml <<'EOF'
scene = "scene.toml"
width = 32
height = 24
[[viewpoints]]
kind = "flowers"
count = 1
[sun]
angles = [[200.0, 40.0]]
EOF

# openat shows which files a process creates, fsync/fdatasync which it flushes (-y: the path of
# each descriptor), the renames what it publishes; mkdir what else changes a folder.
strace -f -y -qq -e signal=none -o trace.txt \
  -e trace=openat,fsync,fdatasync,rename,renameat,renameat2,mkdir,mkdirat \
  sh -c '
    "$0" --quiet build scene.toml --out field &&
    "$0" --quiet build scene.toml --out field &&
    "$0" --quiet tileset --set cohen8 --per-tile 6 --relax 5 --seed 3 --out tiles.json >/dev/null &&
    "$0" --quiet scatter --tileset tiles.json --plane 16x16 --tile-size 4 --out points.csv &&
    "$0" --quiet batch run one.toml --out batch --workers 1 >/dev/null
  ' "$bin" || fail "a command failed under strace (trace: $dir/trace.txt)"

scene_folder=$(ls -d batch/scenes/*/ 2>/dev/null | head -n 1)
[ -n "$scene_folder" ] || fail "the batch built no scene folder"
python3 "$checker" trace.txt "$dir" \
  field field/scene.pov field/scene.cache field/tiles.ldi field/scene.glb field/blender field/scene.toml \
  tiles.json points.csv \
  "${scene_folder%/}" batch/stills/0000.png batch/tasks/0000.json batch/plan.json batch/batch.json \
  batch/index.html batch/contact-sheet.png
