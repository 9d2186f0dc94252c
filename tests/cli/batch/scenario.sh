#!/bin/sh
# scenario.sh NAME WANGSCAPE DIR: one `wangscape batch` test (tests/cli/batch.cmake) in DIR,
# which holds tiny.toml and four.toml (4 tiny stills: 2 viewpoints x 2 suns).
set -u
name=$1
bin=$2
dir=$3
here=$(cd "$(dirname "$0")" && pwd)
cd "$dir" || exit 1
fail() { echo "FAIL ($name): $*" >&2; exit 1; }
# Every link of DIR/index.html (the scene folder, the log, the inputs of each still) exists, and
# each still has all three.
check_links() {
  python3 - "$1" <<'PY' || fail "gallery links: $1"
import json, os, re, sys
d = sys.argv[1]
html = open(d + "/index.html").read()
links = re.findall(r'<a href="([^"]+)">(scene folder|\w+ log|inputs)</a>', html)
tasks = json.load(open(d + "/batch.json"))["tasks"]
assert len(links) == 3 * len(tasks), (len(links), len(tasks))
for target, what in links:
    assert os.path.exists(os.path.join(d, target)), (target, what)
PY
}
# Every task of a batch.json rendered exactly once, and `count` done.
check_once() {
  python3 - "$1" "$2" <<'PY' || fail "batch.json: $1"
import json, sys
b = json.load(open(sys.argv[1] + "/batch.json"))
n = int(sys.argv[2])
assert b["done"] == n and len(b["tasks"]) == n, (b["done"], len(b["tasks"]))
assert all(t["renders"] == 1 for t in b["tasks"]), [t["renders"] for t in b["tasks"]]
assert b["renders_total"] == n, b["renders_total"]
PY
}
case "$name" in
plan)
  "$bin" batch plan four.toml | grep -q "^4 tasks" || fail "plan does not say 4 tasks"
  "$bin" batch plan four.toml --json | python3 -c '
import json, sys
tasks = json.load(sys.stdin)
assert len(tasks) == 4, len(tasks)
for t in tasks:
    for key in ("dem", "camera", "sun", "engine", "width", "height", "input_hash"):
        assert key in t, key
    assert len(t["camera"]["position_enu"]) == 3 and "latitude" in t["camera"]
    assert t["engine"] == "povray" and t["width"] == 48
    assert "azimuth" in t["sun"] and "elevation" in t["sun"]
assert len({t["input_hash"] for t in tasks}) == 4
' || fail "plan --json shape"
  printf 'scene = "tiny.toml"\n[[paths]]\nfile = "nowhere.json"\n' > nopath.toml
  sh "$here/../expect.sh" 1 "nopath.toml:2: \\[\\[paths\\]\\] file: .*nowhere.json" "$bin" batch plan nopath.toml ||
    fail "a missing path file is not named with its line"
  printf 'scene = "tiny.toml"\n[[paths]]\nfile = "walk.json"\nfps = 500\n' > fastpath.toml
  sh "$here/../expect.sh" 1 "fastpath.toml:4: 'paths.fps' is 500; expected frames a second from 1 to 240" "$bin" batch plan fastpath.toml ||
    fail "a path's fps out of range is not refused"
  printf 'scene = "tiny.toml"\n[[viewpoints]]\nknd = "grid"\n' > typo.toml
  sh "$here/../expect.sh" 1 "typo.toml:3: unknown key .viewpoints.knd." "$bin" batch plan typo.toml ||
    fail "an unknown key is not named with its line"
  ;;
example)
  "$bin" batch example > example.toml || fail "batch example"
  grep -q '^scene = "default"' example.toml || fail "example does not use the default scene"
  "$bin" --quiet batch plan example.toml > example-plan.txt || fail "the example does not plan"
  grep -q "^4 tasks" example-plan.txt || fail "the example is not 2 viewpoints x 2 suns"
  ;;
local)
  rm -rf local
  "$bin" --quiet batch run four.toml --out local --workers 2 || fail "first run"
  for f in index.html contact-sheet.png batch.json stills/0000.png stills/0003.png; do
    [ -s "local/$f" ] || fail "local/$f missing"
  done
  grep -c '<img src="stills/' local/index.html | grep -q '^4$' || fail "gallery does not show 4 stills"
  # Under each thumbnail two lines of text (issue 40): light pixels in the grey strip (28 pixels)
  # below the last row's first still, which a sheet without labels does not reach (its grey is
  # 0.2; the text is drawn at 0.92).
  thumb_h=$(oiiotool --info local/stills/0000.png |
    awk '{ for (i = 2; i < NF; ++i) if ($i == "x") { w = $(i - 1); h = $(i + 1); sub(",", "", h) } }
         END { print int(160 * h / w) }')
  oiiotool local/contact-sheet.png --cut "160x24+4+$((4 + thumb_h + 32 + thumb_h))" --printstats 2>/dev/null |
    awk '/Max:/ { found = 1; if ($3 + 0 < 0.6) exit 1 } END { if (!found) exit 1 }' ||
    fail "the contact sheet has no label under its first still"
  # Each still links to its scene folder, its engine's log and its inputs, which exist (issue 24).
  check_links local
  check_once local 4
  before=$(ls -l --time-style=+%s.%N local/stills local/tasks | md5sum)
  "$bin" --quiet batch run four.toml --out local --workers 2 || fail "rerun"
  after=$(ls -l --time-style=+%s.%N local/stills local/tasks | md5sum)
  [ "$before" = "$after" ] || fail "the rerun touched stills or task records"
  check_once local 4
  "$bin" batch status local | grep -q "done 4, running 0, failed 0, pending 0" || fail "status"
  # One summary line on stderr, no progress bar off a terminal; nothing with --quiet (issue 24).
  "$bin" batch run four.toml --out local --workers 2 2> summary.txt > /dev/null || fail "summary run"
  [ "$(wc -l < summary.txt)" = 1 ] && grep -Eq '^wangscape: wrote local \(4 stills, 0 failed, gallery local/index.html, [0-9.]+ [kM]?B\) in ' summary.txt ||
    { cat summary.txt; fail "not one summary line on stderr"; }
  "$bin" --quiet batch run four.toml --out local --workers 2 2> quiet.txt > /dev/null || fail "quiet run"
  [ -s quiet.txt ] && fail "--quiet still wrote to stderr"
  ;;
embree)
  # Embree stills beside POV-Ray's, each with its task's sun: the two suns give two pictures, and
  # each engine's mean brightness is near the other's at the same sun.
  rm -rf engines
  "$bin" --quiet batch run engines.toml --out engines --workers 2 || fail "embree batch run"
  check_links engines
  check_once engines 4
  python3 - engines <<'PY' || fail "embree stills"
import json, subprocess, sys
d = sys.argv[1]
tasks = json.load(open(d + "/batch.json"))["tasks"]
def mean(path):
    out = subprocess.run(["oiiotool", path, "--printstats"], capture_output=True, text=True).stdout
    line = next(l for l in out.splitlines() if "Stats Avg" in l)
    rgb = [float(v) for v in line.split(":")[1].split()[:3]]
    return sum(rgb) / 3 / (255 if "of 255" in line else 1)
stills = {(t["engine"], t["sun"]["azimuth"]): d + "/stills/" + t["id"] + ".png" for t in tasks}
assert sorted(stills) == [("embree", 120.0), ("embree", 240.0), ("povray", 120.0), ("povray", 240.0)], sorted(stills)
a, b = (open(stills[("embree", s)], "rb").read() for s in (120.0, 240.0))
assert a != b, "the two suns gave the same Embree still"
for sun in (120.0, 240.0):
    e, p = mean(stills[("embree", sun)]), mean(stills[("povray", sun)])
    assert abs(e - p) < 0.05, (sun, e, p)  # measured 0.015 apart
    print("sun", sun, "mean embree", round(e, 3), "povray", round(p, 3))
PY
  grep -q -- "--sun=120,30" engines/work/*/embree.log || fail "no Embree log names its task's sun"
  ;;
paths)
  # A path's frames split into tasks: every frame once in paths/1-walk-ENGINE/, path.mp4 when every
  # part is done; a kill after the first part leaves its frames, which the rerun keeps.
  rm -rf paths
  "$bin" batch plan paths.toml | grep -q "^0003  flat ground  path walk frames 3-5 " || fail "plan: no part of frames 3-5"
  setsid "$bin" --quiet batch run paths.toml --out paths --workers 1 > paths-run.log 2>&1 &
  pid=$!
  i=0
  while [ ! -e paths/tasks/0002.json ] && [ $i -lt 600 ]; do sleep 0.05; i=$((i + 1)); done
  kill -s KILL -- "-$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  [ -e paths/tasks/0002.json ] || fail "the first part never finished"
  [ -e paths/tasks/0007.json ] && fail "the killed run finished every part (kill it earlier)"
  first=$(ls -l --time-style=+%s.%N paths/paths/1-walk-povray/frame-00000.png paths/paths/1-walk-povray/frame-00002.png)
  "$bin" --quiet batch run paths.toml --out paths --workers 2 || fail "paths run after the kill"
  check_once paths 8
  check_links paths
  [ "$(ls -l --time-style=+%s.%N paths/paths/1-walk-povray/frame-00000.png paths/paths/1-walk-povray/frame-00002.png)" = "$first" ] ||
    fail "the rerun rendered the killed run's finished frames again"
  for engine in povray embree; do
    [ "$(ls paths/paths/1-walk-$engine | grep -c '^frame-0000[0-7].png$')" = 8 ] || fail "$engine: not 8 frames"
    if command -v ffmpeg > /dev/null; then
      [ -s "paths/paths/1-walk-$engine/path.mp4" ] || fail "$engine: no path.mp4"
    fi
  done
  grep -q '<a href="paths/1-walk-embree/path.mp4">' paths/index.html || fail "the gallery does not link the movie"
  ;;
kill)
  rm -rf killed
  setsid "$bin" --quiet batch run four.toml --out killed --workers 1 > kill-run.log 2>&1 &
  pid=$!
  i=0
  while [ ! -e killed/tasks/0000.json ] && [ $i -lt 600 ]; do sleep 0.05; i=$((i + 1)); done
  kill -s KILL -- "-$pid" 2>/dev/null  # the run, its workers and their POV-Ray
  wait "$pid" 2>/dev/null
  [ -e killed/tasks/0000.json ] || fail "the first still never finished"
  "$bin" batch status killed
  [ -e killed/index.html ] && fail "the killed run got to its gallery (kill it earlier)"
  "$bin" --quiet batch run four.toml --out killed --workers 1 || fail "rerun after the kill"
  check_once killed 4
  ;;
missing_dem)
  rm -rf missing
  printf 'scene = "tiny.toml"\ndems = ["no-such-valley.dem"]\nwidth = 48\nheight = 36\n' > missing.toml
  sh "$here/../expect.sh" 1 "missing.toml:2: DEM .*no-such-valley.dem.*does not exist" "$bin" batch run missing.toml --out missing ||
    fail "missing DEM not reported"
  [ -e missing/tasks ] && fail "tasks started although a DEM is missing"
  ;;
failing)
  rm -rf failing
  printf 'scene = "tiny.toml"\nengines = ["povray", "blender"]\nwidth = 48\nheight = 36\n[[viewpoints]]\ncount = 1\n[sun]\nangles = [[120.0, 30.0], [240.0, 50.0]]\n' > failing.toml
  WANGSCAPE_BLENDER=/bin/false sh "$here/../expect.sh" 1 "task 0001 .*failed: .*log: .*blender.log" \
    "$bin" batch run failing.toml --out failing --workers 2 || fail "failure not reported with its log"
  [ -s failing/stills/0000.png ] && [ -s failing/stills/0002.png ] || fail "the POV-Ray stills did not finish"
  "$bin" batch status failing | grep -q "done 2, running 0, failed 2, pending 0" || fail "status of failures"
  python3 -c 'import json; b = json.load(open("failing/batch.json")); assert b["failed"] == 2 and b["tasks"][1]["failure"]["log"]' ||
    fail "batch.json does not record the failures"
  # The gallery shows each failed still with its error and links to the Blender log (issue 24).
  [ "$(grep -c 'class="failed">failed: ' failing/index.html)" = 2 ] || fail "the gallery does not show the 2 errors"
  grep -q '<a href="work/0001/blender.log">blender log</a>' failing/index.html || fail "no link to the failed task's log"
  grep -q '<a href="scenes/[0-9a-f]*/">scene folder</a>' failing/index.html || fail "no link to a scene folder"
  check_links failing
  ;;
slurm)
  command -v slurmctld > /dev/null && command -v munged > /dev/null || { echo "Slurm not installed"; exit 77; }
  [ "$(id -u)" -eq 0 ] || { echo "the test cluster runs its daemons as root"; exit 77; }
  rm -rf slurm-cluster slurm-out slurm-local
  . "$here/slurm_cluster.sh"
  trap stop_slurm_cluster EXIT
  start_slurm_cluster "$dir/slurm-cluster" || fail "the cluster did not start"
  "$bin" --quiet batch run four.toml --out slurm-local --workers 2 || fail "local run"
  "$bin" --quiet batch run four.toml --out slurm-out --executor slurm --chunk 2 --throttle 2 || fail "slurm run"
  ls slurm-out/logs/slurm-*_*.log > /dev/null 2>&1 || fail "no Slurm array element logs"
  ls slurm-out/logs/slurm-assemble-*.log > /dev/null 2>&1 || fail "no assemble job log"
  for f in local/../slurm-local/stills/*.png; do
    cmp "$f" "slurm-out/stills/$(basename "$f")" || fail "$(basename "$f") differs between local and Slurm"
  done
  check_once slurm-out 4
  [ -s slurm-out/index.html ] && [ -s slurm-out/contact-sheet.png ] || fail "no gallery from the Slurm run"
  "$bin" batch status slurm-out | grep -q "done 4, running 0" || fail "status after Slurm"
  # A path's parts as array elements: 8 frames of each engine, path.mp4 made by the assemble job.
  rm -rf slurm-paths
  "$bin" --quiet batch run paths.toml --out slurm-paths --executor slurm --chunk 2 || fail "slurm paths run"
  check_once slurm-paths 8
  [ "$(ls slurm-paths/paths/1-walk-povray | grep -c '^frame-0000[0-7].png$')" = 8 ] || fail "Slurm: not 8 frames"
  # Failing elements (Blender tasks) are resubmitted once, then reported; the others finish.
  rm -rf slurm-failing
  printf 'scene = "tiny.toml"\nengines = ["povray", "blender"]\nwidth = 48\nheight = 36\n[[viewpoints]]\ncount = 1\n' > slurm-failing.toml
  WANGSCAPE_BLENDER=/bin/false sh "$here/../expect.sh" 1 "task 0001 .*failed: .*log: " \
    "$bin" batch run slurm-failing.toml --out slurm-failing --executor slurm --retries 1 || fail "Slurm failure report"
  [ "$(ls slurm-failing/logs/slurm-*_1.log | wc -l)" = 2 ] || fail "the failed element was not resubmitted once"
  [ -s slurm-failing/stills/0000.png ] || fail "the POV-Ray task did not finish on Slurm"
  ;;
terrain)
  # Every viewpoint kind over a cropped real DEM, suns from-to-step; the path (ENU in dem.toml) in lat/lon.
  origin=$("$bin" batch plan dem.toml --json | python3 -c '
import json, sys
t = [t for t in json.load(sys.stdin) if t["viewpoint"] == "grid 0,0"][0]["camera"]
la, lo = t["latitude"], t["longitude"]
print(f"[[{la:.7f}, {lo:.7f}], [{la + 0.0001:.7f}, {lo:.7f}]]")') ||
    fail "plan of dem.toml"
  sed "s/^enu = .*/latlon = $origin/" dem.toml > dem-latlon.toml
  "$bin" batch plan dem-latlon.toml | grep -q "^10 tasks" || fail "dem-latlon.toml is not 10 tasks"
  "$bin" batch plan dem-latlon.toml | grep -q "summit 1 .*sun 2024-07-15T15:00:00-06:00" || fail "summit or sun time"
  rm -rf terrain
  "$bin" --quiet batch run dem-latlon.toml --out terrain --workers 2 || fail "terrain run"
  check_once terrain 10
  [ "$(ls terrain/scenes | grep -vc lock)" = 1 ] || fail "the 10 stills did not share one scene folder"
  grep -q "lat/lon 40\." terrain/index.html || fail "gallery without lat/lon"
  ;;
*) fail "unknown scenario" ;;
esac
echo "ok: $name"
