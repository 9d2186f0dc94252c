#!/bin/sh
# hostile_batch.sh NAME WANGSCAPE DIR SOURCE: one hostile batch case (issue 25,
# tests/cli/hostile_batch.cmake) in DIR, which holds tiny.toml; SOURCE is the source tree. Each is refused with its exit code and a message naming the file,
# the place and what was expected, without raw library text; none needs a renderer.
set -u
name=$1
bin=$2
dir=$3
source=$4
here=$(cd "$(dirname "$0")" && pwd)
cd "$dir" || exit 1
fail() { echo "FAIL ($name): $*" >&2; exit 1; }
# refuse CODE PATTERN COMMAND...: exit CODE, output matching PATTERN, no library text, no hang.
refuse() { sh "$here/refuse.sh" "$@" || fail "refused otherwise"; }
# batch NAME LINES...: a batch file NAME.toml over tiny.toml with these lines.
batch() {
  f=$1.toml
  shift
  printf 'scene = "tiny.toml"\nwidth = 48\nheight = 36\n' > "$f"
  for line in "$@"; do printf '%s\n' "$line" >> "$f"; done
}
# plan_folder DIR: DIR/plan.json as `batch run` writes it, for 2 stills, without rendering.
plan_folder() {
  rm -rf "$1" && mkdir -p "$1" || fail "mkdir $1"
  batch plan2 '[[viewpoints]]' 'count = 2'
  "$bin" batch plan plan2.toml --json > "$1/tasks.json" || fail "plan2.toml does not plan"
  python3 - "$1" "$dir" <<'PY' || fail "plan.json"
import json, sys
out, base = sys.argv[1], sys.argv[2]
tasks = json.load(open(out + "/tasks.json"))
scene = {"text": open(base + "/tiny.toml").read(), "source": base + "/tiny.toml", "base_dir": base, "dem": ""}
json.dump({"batch_file": "plan2.toml", "scene": scene, "tasks": tasks}, open(out + "/plan.json", "w"))
PY
}
# tamper DIR PYTHON: edits DIR/plan.json's `p` with the statement PYTHON.
tamper() {
  python3 -c "import json; p = json.load(open('$1/plan.json')); $2; json.dump(p, open('$1/plan.json', 'w'))" ||
    fail "tamper"
}
case "$name" in
deep_key)
  python3 -c "print('scene = \"tiny.toml\"\na' + '.a' * 100000 + ' = 1')" > deep.toml
  refuse 1 "deep.toml:2: a key of more than 64 dotted parts" "$bin" batch plan deep.toml
  ;;
not_a_file)
  refuse 1 "^wangscape: error: /dev/zero: the batch file is not a regular file" "$bin" batch plan /dev/zero
  rm -f fifo.toml && mkfifo fifo.toml || fail "mkfifo"
  refuse 1 "fifo.toml: the batch file is not a regular file" "$bin" batch plan fifo.toml
  refuse 1 "$dir: the batch file is not a regular file" "$bin" batch plan "$dir"
  ;;
million_tasks)
  batch million '[[viewpoints]]' 'kind = "grid"' 'grid = [100, 100]' '[sun]' \
    'from = 2024-07-15T09:00:00-07:00' 'to = 2024-07-15T10:39:00-07:00' 'step_minutes = 1'
  refuse 1 "million.toml: the batch asks for up to 1000000 stills .*; at most 100000 are planned: split it" \
    "$bin" batch plan million.toml --json
  refuse 1 "at most 100000 are planned" "$bin" batch run million.toml --out million
  [ -e million ] && fail "a refused batch made its output folder"
  batch suns '[sun]' 'from = 2024-07-15T09:00:00-07:00' 'to = 2044-07-15T10:39:00-07:00' 'step_minutes = 1'
  refuse 1 "suns.toml:.*: 'sun.from' to 'to' every 1 minutes is .* suns; at most 10000" "$bin" batch plan suns.toml
  refuse 2 "--workers: Value 100000 not in range 1 to 256" "$bin" batch run million.toml --out million --workers 100000
  ;;
sun_step)
  # Issue 41: a step of 1e18 minutes overflowed the second sun's time, which then came before 'to'
  # again and again until memory ran out (15-26 s, then a generic out-of-memory line).
  for step in 1e18 1e17 0.5; do
    batch step '[[viewpoints]]' 'count = 1' '[sun]' 'from = 2024-07-15T09:00:00-07:00' \
      'to = 2024-07-15T17:00:00-07:00' "step_minutes = $step"
    refuse 1 "^wangscape: error: step.toml:9: 'sun.step_minutes' is .*; expected minutes from 1 to 1e\+09$" \
      "$bin" batch plan step.toml
  done
  rm -rf step_out
  refuse 1 "step.toml:9: 'sun.step_minutes'" "$bin" batch run step.toml --out step_out
  [ -e step_out ] && fail "a refused batch made its output folder"
  ;;
numbers)
  for fov in 0 -10 180 1e300; do
    batch "fov" '[[viewpoints]]' "fov = $fov"
    refuse 1 "fov.toml:5: 'viewpoints.fov' is .*; expected degrees in \(0, 179\]" "$bin" batch plan fov.toml
  done
  batch grid '[[viewpoints]]' 'kind = "grid"' 'grid = [1e300, 1]'
  refuse 1 "grid.toml:6: 'viewpoints.grid' must be \[columns, rows\]" "$bin" batch plan grid.toml
  batch eye '[[viewpoints]]' 'eye_height = 1e300'
  refuse 1 "eye.toml:5: 'viewpoints.eye_height' is 1e\+300; expected meters above the ground from 0 to 20000" \
    "$bin" batch plan eye.toml
  for angle in nan inf -inf; do
    batch sun '[sun]' "angles = [[$angle, 30.0]]"
    refuse 1 "sun.toml:5: 'sun.angles' must hold finite numbers" "$bin" batch plan sun.toml
    batch sun '[sun]' "angles = [[120.0, $angle]]"
    refuse 1 "sun.toml:5: 'sun.angles' must hold finite numbers" "$bin" batch plan sun.toml
  done
  batch sun '[sun]' 'angles = [[120.0, 1e300]]'
  refuse 1 "sun.toml:5: 'sun.angles' elevation 1e\+300: expected degrees in \(0, 90\]" "$bin" batch plan sun.toml
  batch path '[[viewpoints]]' 'kind = "path"' 'enu = [[1.0, 2.0], [1.0, 2.0], [1.0, 2.0]]'
  refuse 1 "path.toml:4: path points 1 and 2 are the same place" "$bin" batch plan path.toml
  ;;
out)
  batch one '[[viewpoints]]' 'count = 1'
  refuse 1 "batch run: --out is empty" sh -c 'exec "$0" batch run one.toml --out ""' "$bin"
  touch a-file
  refuse 1 "a-file: the batch output folder exists and is not a folder" "$bin" batch run one.toml --out a-file
  refuse 1 "a-file/x: cannot create the batch output folder: Not a directory" "$bin" batch run one.toml --out a-file/x
  refuse 1 "/proc/wangscape-batch: cannot create the batch output folder" "$bin" batch run one.toml --out /proc/wangscape-batch
  ;;
out_povray)
  # Issue 41: a quote or a newline in --out made the whole output folder, then failed every
  # POV-Ray still (POV-Ray takes its folders in double quotes) and exited 1. Refused first now.
  batch one '[[viewpoints]]' 'count = 1'
  for out in 'q"out' "$(printf 'n\nout')"; do
    rm -rf "$out"
    refuse 1 '^wangscape: error: batch run --out (q"out|n\\nout): POV-Ray cannot use this path: it holds a control character .* or a double quote' \
      "$bin" batch run one.toml --out "$out"
    [ -e "$out" ] && fail "a refused batch made its output folder"
  done
  ;;
plan_ids)
  plan_folder ids
  tamper ids "p['tasks'][0]['id'] = '../../../pwned'"
  refuse 1 "ids/plan.json:task 0: has index 0 and id '../../../pwned'; expected 0 and '0000'" "$bin" batch run-task ids 0
  ls -a .. ../.. ../../.. ids/.. | grep pwned && fail "the task id wrote outside the output folder"
  plan_folder keys
  tamper keys "p['tasks'][1]['scene_key'] = '../../x'"
  refuse 1 "keys/plan.json:task 1: has scene key '../../x'; expected 16 hex digits" "$bin" batch run-task keys 0
  plan_folder types
  tamper types "p['tasks'][1]['sun']['azimuth'] = 'NaN'"
  refuse 1 "types/plan.json:task 1: a field is missing or of the wrong type" "$bin" batch status types
  tamper types "p['tasks'][1]['sun']['azimuth'] = float('nan')"
  refuse 1 "types/plan.json: is not a batch plan: not JSON" "$bin" batch status types
  plan_folder types
  sed -i 's/"fov": 60.0/"fov": 1e5456/' types/plan.json
  refuse 1 "types/plan.json: is not a batch plan: it holds a number too large for a double" "$bin" batch status types
  plan_folder range
  tamper range "p['tasks'][0]['camera']['fov'] = 0"
  refuse 1 "range/plan.json:task 0: has a field of view, a sun elevation or an image size out of range" "$bin" batch status range
  rm -f range/plan.json && mkfifo range/plan.json || fail "mkfifo"
  refuse 1 "range/plan.json: the batch plan is not a regular file" "$bin" batch status range
  ;;
utf8)
  # A DEM whose name is not UTF-8 (byte 0xFF): JSON output gets U+FFFD, not json.exception.
  rm -rf dems && mkdir dems || fail "mkdir"
  name=$(printf 'b\377')
  cp "$source/tests/data/dem/SRTMGL3_boulder_CO_240x144.asc" "dems/$name.asc" || fail "cp"
  cp "$source/tests/data/dem/SRTMGL3_boulder_CO_240x144.prj" "dems/$name.prj" || fail "cp"
  batch utf8 'dem_folder = "dems"' '[[viewpoints]]' 'count = 1'
  refuse 0 "$(printf 'b\357\277\275[.]asc')" "$bin" batch plan utf8.toml --json
  refuse 0 "$(printf 'b\357\277\275[.]asc')" "$bin" terrain info --json "dems/$name.asc"
  ;;
utf8_run)
  # Issue 41: the plan kept such a name as U+FFFD, so the task then failed with "does not exist".
  # plan.json keeps its bytes (dem_bytes, in hex) and the still is rendered (POV-Ray, 48 x 36).
  rm -rf dems utf8_out && mkdir dems || fail "mkdir"
  name=$(printf 'b\377')
  cp "$source/tests/data/dem/SRTMGL3_boulder_CO_240x144.asc" "dems/$name.asc" || fail "cp"
  cp "$source/tests/data/dem/SRTMGL3_boulder_CO_240x144.prj" "dems/$name.prj" || fail "cp"
  batch utf8 'dem_folder = "dems"' '[[viewpoints]]' 'count = 1'
  refuse 0 "wrote utf8_out \(1 stills, 0 failed" "$bin" batch run utf8.toml --out utf8_out --workers 1
  [ -s utf8_out/stills/0000.png ] || fail "no still"
  grep -q '"dem_bytes": "64656d732f62ff2e617363"' utf8_out/plan.json || fail "plan.json lost the name's bytes"
  ;;
lock)
  batch one '[[viewpoints]]' 'count = 1'
  rm -rf locked && mkdir -p locked/logs || fail "mkdir"
  exec 9> locked/logs/run.lock && flock -n 9 || fail "cannot take the lock"
  refuse 1 "locked: another .wangscape batch run. .* is rendering into this folder; wait for it" \
    "$bin" batch run one.toml --out locked
  [ -e locked/stills/0000.png ] && fail "rendered beside the lock holder"
  ;;
*) fail "unknown case" ;;
esac
echo "ok: $name"
