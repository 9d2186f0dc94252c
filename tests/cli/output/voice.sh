#!/bin/sh
# voice.sh WANGSCAPE SOURCE SCRATCH FAMILY: one voice for output (issue 24). A command that writes
# something says so in one line on stderr, "wangscape: wrote PATH[, PATH] (DETAILS, SIZE) in TIME",
# exits 0 and says nothing under --quiet; a failing one exits 1 with one error line and no such
# line. FAMILY: tileset, tiling, tiles (noise and texture), scene (build, render with POV-Ray and
# Embree), ldi (build, sheet). scatter's line is checked by cli_scatter_streams; demo is build
# and render in one (and half a minute), so it is not run here.
set -u
bin=$1
src=$2
scratch=$3
family=$4
rm -rf "$scratch"
mkdir -p "$scratch"
cd "$scratch" || exit 1
ln -s "$src/data" data
ln -s "$src/templates" templates
status=0
fail() { echo "FAIL ($family): $*" >&2; status=1; }

# says 'DISPLAYED PATHS' ARGS...: exit 0, exactly one line on stderr, the wrote line for PATHS.
says() {
  paths=$1
  shift
  "$bin" "$@" > out.txt 2> err.txt
  code=$?
  [ $code -eq 0 ] || { fail "wangscape $*: exit $code: $(cat err.txt)"; return; }
  lines=$(grep -c '' err.txt)
  [ "$lines" -eq 1 ] || fail "wangscape $*: $lines lines on stderr, expected 1: $(cat err.txt)"
  grep -Eq "^wangscape: wrote $paths \((.*, )?[0-9.]+ [kMG]?B\) in [0-9.]+ s$" err.txt ||
    fail "wangscape $*: no 'wrote $paths' line: $(cat err.txt)"
}
# quiet ARGS...: exit 0 and nothing on stderr under --quiet.
quiet() {
  "$bin" --quiet "$@" > out.txt 2> err.txt
  code=$?
  [ $code -eq 0 ] || fail "wangscape --quiet $*: exit $code: $(cat err.txt)"
  [ ! -s err.txt ] || fail "wangscape --quiet $*: said $(cat err.txt)"
}
# refused ARGS...: exit 1, one error line, no wrote line.
refused() {
  "$bin" "$@" > out.txt 2> err.txt
  code=$?
  [ $code -eq 1 ] || fail "wangscape $*: exit $code, expected 1: $(cat err.txt)"
  grep -q '^wangscape: error: ' err.txt || fail "wangscape $*: no error line: $(cat err.txt)"
  ! grep -q 'wrote' err.txt || fail "wangscape $*: a failed run says it wrote: $(cat err.txt)"
}

case "$family" in
tileset)
  says sheet.png tileset --set cohen8 --sheet sheet.png
  says "tiles.json, discs.png" tileset --set cohen8 --per-tile 5 --out tiles.json --sheet discs.png
  grep -q "rho over every configuration" out.txt || fail "the fill's figures left stdout"
  quiet tileset --set cohen8 --per-tile 5 --out quiet.json
  refused tileset --set no-such-set --sheet never.png
  ;;
tiling)
  says map.png tiling --set cohen8 --size 16x16 --out map.png
  says window.csv tiling --set cohen8 --size 16x16 --out window.csv --stats
  quiet tiling --set cohen8 --size 16x16 --out quiet.png
  refused tiling --set no-such-set --size 4x4 --out never.png
  ;;
tiles)
  says "noise, noise.png" noise tiles --set corner-2 --lattice 8 --out noise --preview 64x32 noise.png
  says tex texture tiles --exemplar pumice --set corner-2 --size 32 --out tex
  quiet noise tiles --set corner-2 --lattice 8 --out quiet
  refused texture tiles --exemplar no-such-image.png --set corner-2 --out never
  ;;
scene)
  says small build templates/scenes/small.toml --out small
  grep -Eq "^wangscape: wrote small \(tiles: [0-9]+ visible, .*flowers: [0-9]+ models, 0 proxies, [0-9.]+ MB\)" err.txt ||
    fail "build's line lacks its counts: $(cat err.txt)"
  says small/render.png render small
  grep -q "povray; log small/povray.log" err.txt || fail "render's line lacks its log: $(cat err.txt)"
  says small/embree.png render small --engine embree --spp 1 --out small/embree.png
  quiet build templates/scenes/small.toml --out small
  quiet render small --engine embree --spp 1 --out small/quiet.png
  refused render no-such-folder
  refused build no-such-scene.toml --out never
  ;;
ldi)
  says pack.ldi ldi build templates/scenes/small.toml --out pack.ldi --levels 1 --directions 2
  grep -Eq "\([0-9]+ LDIs, " err.txt || fail "ldi build's line lacks its count: $(cat err.txt)"
  says sheet.png ldi sheet pack.ldi --tile 0 --out sheet.png
  quiet ldi sheet pack.ldi --tile 1 --out quiet.png
  refused ldi sheet pack.ldi --tile 999 --out never.png
  ;;
*) fail "unknown family" ;;
esac
[ $status -eq 0 ] && echo "ok ($family)"
exit $status
