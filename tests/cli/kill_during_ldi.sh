#!/bin/sh
# kill_during_ldi.sh WANGSCAPE SCENE SIGNAL: builds SCENE (with [exports] ldi) into a folder, then
# builds a changed scene (another seed) into the same folder and sends SIGNAL once that build is
# sampling its LDI pack (its tiles.ldi being written in the staging folder). Passes when the
# folder is byte for byte the first build's (scene, writers' files, pack, scene.cache), and after
# one more build nothing of the killed run is left beside it.
bin=$1
scene=$2
signal=$3
fail() {
  echo "kill_during_ldi: $*" >&2
  exit 1
}
work=$(mktemp -d) || fail "no temporary folder"
trap 'rm -rf "$work"' EXIT
out="$work/field"
"$bin" --quiet build "$scene" --out "$out" || fail "the first build failed"
[ -s "$out/tiles.ldi" ] || fail "the first build wrote no tiles.ldi"
(cd "$out" && find . -type f | sort | xargs sha256sum) >"$work/first.sums"

sed 's/^seed = .*/seed = 77/' "$scene" >"$work/second.toml"
env --default-signal=INT "$bin" --quiet build "$work/second.toml" --out "$out" 2>"$work/second.err" &
pid=$!
. "$(dirname "$0")/wait_for_start.sh"
# The staging folder and its pack's temporary both carry the pid.
wait_for_start "$pid" "$work" ".field.partial-$pid/.tiles.ldi.tmp-*" 60 || {
  kill -KILL "$pid" 2>/dev/null
  fail "the second build never reached its LDI stage; stderr: $(cat "$work/second.err")"
}
kill "-$signal" "$pid"
wait "$pid"
code=$?
[ "$code" -ne 0 ] || fail "the killed build exited 0"
(cd "$out" && find . -type f | sort | xargs sha256sum) >"$work/after.sums"
cmp -s "$work/first.sums" "$work/after.sums" || fail "the folder changed: $(diff "$work/first.sums" "$work/after.sums")"
echo "kill_during_ldi: SIG$signal during the LDI stage -> exit $code, the folder is the first build's"

# The next build clears what a killed run (SIGKILL leaves its staging folder) left beside it.
"$bin" --quiet build "$scene" --out "$out" || fail "the build after the kill failed"
left=$(find "$work" -maxdepth 1 -name '.*.partial-*')
[ -z "$left" ] || fail "left behind: $left"
(cd "$out" && find . -type f | sort | xargs sha256sum) >"$work/third.sums"
cmp -s "$work/first.sums" "$work/third.sums" || fail "the same scene built again differs"
echo "kill_during_ldi: nothing left beside the folder after the next build"
