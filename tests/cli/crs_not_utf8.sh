#!/bin/sh
# crs_not_utf8.sh WANGSCAPE SOURCE DIR: a DEM whose CRS name holds the byte 0xFF (a Latin-1 .prj).
# `terrain info --json` and every JSON a build writes (manifest.json, the glTF's JSON chunk) parse
# as UTF-8 JSON with U+FFFD in its place, scene.pov stays UTF-8, and POV-Ray renders it.
wangscape=$1
source=$2
dir=$3
fail() {
  echo "crs_not_utf8: $*" >&2
  exit 1
}
rm -rf "$dir" && mkdir -p "$dir" || fail "cannot create $dir"
cd "$dir" || fail "cd $dir"
cp "$source/tests/data/dem/SRTMGL3_boulder_CO_240x144.asc" d.asc || fail "cp"
sed 's/GCS_WGS_1984/GCS_WGS_\xff1984/' "$source/tests/data/dem/SRTMGL3_boulder_CO_240x144.prj" >d.prj || fail "sed"
grep -q "$(printf 'WGS_\377')" d.prj || fail "the .prj holds no 0xFF"
cat >s.toml <<'TOML'
name = "crs"
[terrain]
dem = "d.asc"
crop = [-600.0, -600.0, 600.0, 600.0]
[tiles]
points_per_tile = 6
area = [-24.0, -24.0, 24.0, 24.0]
[models]
variants = 2
triangle_budget = 400
[image]
width = 48
height = 36
[exports]
povray = true
gltf = true
blender = true
TOML
"$wangscape" --quiet terrain info --json d.asc >info.json || fail "terrain info failed"
"$wangscape" --quiet build s.toml --out out || fail "the build failed"
"$wangscape" --quiet render out || fail "POV-Ray could not render scene.pov"
python3 - <<'PY' || fail "an output is not UTF-8 JSON with U+FFFD for the byte"
import json, struct
info = json.load(open("info.json", encoding="utf-8"))
assert info["crs_name"] == "GCS_WGS_\ufffd1984", info["crs_name"]
manifest = json.load(open("out/blender/manifest.json", encoding="utf-8"))
assert "GCS_WGS_\ufffd1984" in json.dumps(manifest, ensure_ascii=False)
glb = open("out/scene.glb", "rb").read()
length = struct.unpack("<I", glb[12:16])[0]
gltf = json.loads(glb[20:20 + length].decode("utf-8"))
assert "GCS_WGS_\ufffd1984" in json.dumps(gltf, ensure_ascii=False)
pov = open("out/scene.pov", "rb").read().decode("utf-8")  # raises on a raw 0xFF
assert "GCS_WGS_\ufffd1984" in pov
PY
echo "crs_not_utf8: U+FFFD in terrain info, manifest.json, scene.glb and scene.pov; POV-Ray rendered"
