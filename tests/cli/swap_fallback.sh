#!/bin/sh
# swap_fallback.sh WANGSCAPE SCENE DIR: rebuilds a scene folder on a filesystem that refuses
# renameat2's RENAME_EXCHANGE (bindfs, a FUSE filesystem: EINVAL), where the build falls back to
# two renames. Passes when the rebuild says so on stderr, exits 0, replaces the old build (a file
# planted in it is gone) and leaves no .NAME.old-* or .NAME.partial-* behind. Exit 77 (skipped)
# when bindfs is missing or FUSE cannot mount here.
wangscape=$1
scene=$2
dir=$3
fail() {
  echo "swap_fallback: $*" >&2
  exit 1
}
command -v bindfs >/dev/null || {
  echo "swap_fallback: skipped: no bindfs (apt install bindfs)"
  exit 77
}
mkdir -p "$dir/backing" "$dir/mount" || fail "cannot create $dir"
fusermount -u "$dir/mount" 2>/dev/null
bindfs "$dir/backing" "$dir/mount" 2>"$dir/bindfs.err" || {
  echo "swap_fallback: skipped: FUSE cannot mount here: $(cat "$dir/bindfs.err")"
  exit 77
}
trap 'fusermount -u "$dir/mount"' EXIT
out="$dir/mount/field"
rm -rf "$out"
"$wangscape" --quiet build "$scene" --out "$out" || fail "the first build failed"
: >"$out/planted-in-the-old-build"
"$wangscape" build "$scene" --out "$out" 2>"$dir/rebuild.err" || fail "the rebuild failed: $(cat "$dir/rebuild.err")"
grep -q "warning: this filesystem cannot exchange two folders at once" "$dir/rebuild.err" ||
  fail "the rebuild did not say it fell back to two renames: $(cat "$dir/rebuild.err")"
[ -s "$out/scene.toml" ] || fail "no scene.toml in the rebuilt folder"
[ ! -e "$out/planted-in-the-old-build" ] || fail "the old build is still in place"
left=$(ls -a "$dir/mount" | grep -E '^\.field\.') && fail "left behind: $left"
echo "swap_fallback: rebuilt with two renames where RENAME_EXCHANGE is refused, nothing left"
