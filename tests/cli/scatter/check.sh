#!/bin/sh
# check.sh BIN SCRATCH MODE [DEM]: one scatter CLI check; exits non-zero with a message on failure.
set -eu
BIN=$1
DIR=$2
MODE=$3
DEM=${4:-}
rm -rf "$DIR"
mkdir -p "$DIR"
cd "$DIR"
fail() { echo "FAIL ($MODE): $*" >&2; exit 1; }
# Debian's python3 has numpy and scipy (a pyenv one earlier on PATH may not).
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3

fill() { # fill SET OUT
  "$BIN" -q tileset --set "$1" --per-tile 12 --relax 20 --seed 3 --out "$2" > fill.log || fail "tileset --per-tile $1"
}

# Pairs closer than the packing diameter (from the JSON, times the tile size) in a CSV.
check_csv() { # check_csv CSV JSON TILE_SIZE
  "$PY" - "$1" "$2" "$3" <<'PY'
import csv, json, sys
import numpy as np
from scipy.spatial import cKDTree
rows = list(csv.reader(open(sys.argv[1])))
assert rows[0] == ["x", "y", "z", "variant", "yaw", "scale", "tile"], rows[0]
pts = np.array([[float(r[0]), float(r[1])] for r in rows[1:]])
doc = json.load(open(sys.argv[2]))
d = 2 * doc["radius_packing"] * float(sys.argv[3])
assert len(pts) > 100, len(pts)
pairs = cKDTree(pts).query_pairs(d * (1 - 1e-5))
assert not pairs, f"{len(pairs)} pairs closer than {d}"
variants = {int(r[3]) for r in rows[1:]}
assert max(variants) < doc["variants"] and len(variants) > 1, variants
tiles = {int(r[6]) for r in rows[1:]}
assert max(tiles) < len(doc["tiles"]), tiles
PY
}

case "$MODE" in
fill)
  "$BIN" -q tileset --set cohen8 --per-tile 12 --relax 20 --seed 3 --out tiles.json --sheet sheet.png > fill.log
  grep -q "rho over every configuration" fill.log || fail "no summary line"
  [ -s sheet.png ] || fail "no sheet"
  "$PY" - <<'PY'
import json
doc = json.load(open("tiles.json"))
assert doc["format"] == "wangscape-filled-tileset" and doc["name"] == "cohen8", doc.keys()
assert 0 < doc["radius_tight"] < doc["radius_packing"] < 0.5
assert len(doc["tiles"]) == 8
ids = {}
for t in doc["tiles"]:
    assert set(t) >= {"n", "e", "s", "w", "points"}
    assert len(t["points"]) >= 8
    for p in t["points"]:
        assert 0 <= p["x"] < 1 and 0 <= p["y"] < 1
        key = (p["x"], p["y"], p["variant"], p["yaw"], p["scale"])
        assert ids.setdefault(p["id"], key) == key, "replica differs"
PY
  # The filled file is also a plain tile set for the color readers.
  "$BIN" tileset --set tiles.json | grep -q "tiles:   8" || fail "filled set not readable as a tile set"
  ;;
csv)
  fill cohen8 tiles.json
  "$BIN" -q scatter --tileset tiles.json --plane 48x40 --tile-size 4 --out points.csv
  check_csv points.csv tiles.json 4
  ;;
ply)
  fill cohen8 tiles.json
  "$BIN" -q scatter --tileset tiles.json --plane 48x40 --tile-size 4 --seed 9 --out points.csv
  "$BIN" -q scatter --tileset tiles.json --plane 48x40 --tile-size 4 --seed 9 --out points.ply
  "$PY" - <<'PY'
import csv, struct
data = open("points.ply", "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode().split("\n")
assert header[1] == "format binary_little_endian 1.0", header
count = int([l for l in header if l.startswith("element vertex")][0].split()[2])
rows = list(csv.reader(open("points.csv")))[1:]
assert count == len(rows), (count, len(rows))
assert len(data) - end == count * 26, (len(data) - end, count)
for k in (0, count // 2, count - 1):
    x, y, z, v, yaw, s, t = struct.unpack_from("<fffHffI", data, end + 26 * k)
    r = rows[k]
    assert (x, y, v, t) == (struct.unpack("f", struct.pack("f", float(r[0])))[0],
                            struct.unpack("f", struct.pack("f", float(r[1])))[0], int(r[3]), int(r[6])), (k, r)
PY
  ;;
metrics)
  fill cohen8 tiles.json
  "$BIN" -q scatter --tileset tiles.json --plane 128x128 --tile-size 4 --metrics --json --spectrum-png spectrum.png > m.json
  [ -s spectrum.png ] || fail "no spectrum plot"
  "$PY" - <<'PY'
import json
m = json.load(open("m.json"))
assert m["close_pairs"] == 0, m["close_pairs"]
assert m["rho"] > 0.72, m["rho"]
assert 0.7 < m["edge_density_ratio"] < 1.3 and 0.6 < m["corner_density_ratio"] < 1.4, m
assert m["nn_spread"] >= 0.02, m["nn_spread"]
assert len(m["spectrum"]["power"]) > 10
PY
  "$BIN" -q scatter --tileset tiles.json --plane 64x64 --metrics | grep -q "^rho" || fail "text metrics"
  ;;
hash)
  fill complete-edge-2 complete.json
  "$BIN" -q scatter --tileset complete.json --plane 40x40 --tile-size 2 --algorithm hash --out hashed.csv
  check_csv hashed.csv complete.json 2
  fill cohen8 tiles.json
  if "$BIN" -q scatter --tileset tiles.json --plane 40x40 --algorithm hash --out bad.csv 2> err.txt; then
    fail "hash over an incomplete set succeeded"
  fi
  grep -q "complete" err.txt || fail "message does not say the set must be complete: $(cat err.txt)"
  [ ! -e bad.csv ] || fail "partial output left behind"
  ;;
deterministic)
  fill cohen8 a.json
  fill cohen8 b.json
  cmp -s a.json b.json || fail "same seed, different filled sets"
  "$BIN" -q scatter --tileset a.json --plane 64x48 --out a.ply
  "$BIN" -q scatter --tileset a.json --plane 64x48 --out b.ply
  cmp -s a.ply b.ply || fail "same seed, different PLY"
  ;;
errors)
  set +e
  "$BIN" scatter --tileset missing.json --out out.csv 2> err1.txt; code=$?
  [ $code -eq 1 ] || fail "missing tile set: exit $code"
  grep -q "wangscape: error: .*missing.json" err1.txt || fail "message: $(cat err1.txt)"
  [ ! -e out.csv ] || fail "partial output"
  echo '{"name": "x", "tiles": [{"n":0,"e":0,"s":0,"w":0}]}' > plain.json
  "$BIN" scatter --tileset plain.json --out out.csv 2> err2.txt; code=$?
  [ $code -eq 1 ] || fail "plain tile set: exit $code"
  grep -q "format" err2.txt || fail "message: $(cat err2.txt)"
  "$BIN" scatter --out out.csv 2> /dev/null; code=$?
  [ $code -eq 2 ] || fail "no --tileset: exit $code, expected 2"
  "$BIN" tileset --set cohen8 --per-tile 5 --out t.json > /dev/null || fail "fill"
  "$BIN" scatter --tileset t.json --plane 64by64 --out out.csv 2> err3.txt; code=$?
  [ $code -eq 1 ] && grep -q "plane" err3.txt || fail "bad --plane: exit $code $(cat err3.txt)"
  [ ! -e out.csv ] || fail "partial output"
  ;;
streams)
  # Streaming has no count cap: the 8.4 million 4 m tiles of St. Helens hold about 100 million
  # points, which the old cap (50 million, counted before the masks) refused; below 760 m about
  # half a million are placed and written.
  fill cohen8 tiles.json
  "$BIN" scatter --tileset tiles.json --dem "$DEM" --tile-size 4 --max-height 760 --out low.ply 2> said.txt \
    || fail "scatter below 760 m: $(cat said.txt)"
  grep -Eq "^wangscape: wrote low.ply \([0-9]{6} instances from [0-9]+ tiles, [0-9.]+ MB\) in [0-9.]+ s$" said.txt \
    || fail "no one-line summary: $(cat said.txt)"
  count=$(sed -n 's/^element vertex \([0-9]*\).*/\1/p' low.ply | head -n 1)
  [ "$count" -gt 200000 ] || fail "only $count points"
  "$BIN" -q scatter --tileset tiles.json --dem "$DEM" --tile-size 4 --max-height 760 --out quiet.ply 2> quiet.txt \
    || fail "quiet scatter"
  [ ! -s quiet.txt ] || fail "--quiet said: $(cat quiet.txt)"
  cmp -s low.ply quiet.ply || fail "same scatter, different bytes"
  set +e
  # A cap for those who want one: refused by the estimate after the masks, nothing written.
  "$BIN" scatter --tileset tiles.json --dem "$DEM" --tile-size 4 --max-height 760 --max-instances 100000 \
    --out capped.ply 2> err1.txt; code=$?
  [ $code -eq 1 ] || fail "--max-instances 100000: exit $code"
  grep -Eq "after the masks\) would place about [0-9.e+]+ instances; --max-instances is 100000" err1.txt \
    || fail "cap message: $(cat err1.txt)"
  [ ! -e capped.ply ] || fail "partial output under the cap"
  # A file larger than the disk is refused before the first byte, naming the folder and sizes.
  mkdir -p out
  "$BIN" scatter --tileset tiles.json --plane 1e8x1e8 --tile-size 1 --out out/huge.csv 2> err2.txt; code=$?
  [ $code -eq 1 ] || fail "huge plane: exit $code"
  grep -Eq "^wangscape: error: out: scatter's points file 'out/huge.csv' \(about 1\.[0-9]+e\+17 instances.*would need about [0-9.]+ [A-Z]B; the folder has [0-9.]+ [kMGTP]?B free" err2.txt \
    || fail "disk message: $(cat err2.txt)"
  [ -z "$(ls out)" ] || fail "partial output: $(ls out)"
  # Where the points are held (--metrics), memory is the limit.
  "$BIN" scatter --tileset tiles.json --plane 1e6x1e6 --metrics 2> err3.txt; code=$?
  [ $code -eq 1 ] || fail "metrics over a huge plane: exit $code"
  grep -q "scatter --metrics over about .* would need about .* of memory" err3.txt || fail "memory message: $(cat err3.txt)"
  "$BIN" scatter --tileset tiles.json --plane 64x64 --max-instances 0 --out zero.csv 2> /dev/null; code=$?
  [ $code -eq 2 ] || fail "--max-instances 0: exit $code, expected 2"
  ;;
*) fail "unknown mode" ;;
esac
echo "ok ($MODE)"
