#!/bin/sh
# Batch renders (issue 12): a 16-still batch (4 viewpoints among the flowers x 4 suns, 96x72
# POV-Ray stills over the tiny flat test scene) with the local executor and with a real
# single-node Slurm cluster started here (tests/cli/batch/slurm_cluster.sh; needs root).
# Prints wall time, stills per minute, the mean task time recorded in batch.json (scene reuse +
# POV-Ray) and the per-task overhead: (wall x parallel workers - sum of task times) / stills,
# i.e. what scheduling, process start-up and assembling cost on top of the renders; plus the
# cost of one scene build, which every still after the first of a scene does not pay.
# Usage: bench/batch_bench.sh [path/to/wangscape] [scratch dir]
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/release/cli/wangscape}
scratch=${2:-${TMPDIR:-/tmp}/wangscape_batch_bench}
rm -rf "$scratch"
mkdir -p "$scratch"
cd "$scratch"
sed -e 's/@SUN@/azimuth = 200.0\nelevation = 40.0/' -e 's/@EXPORTS@/povray = true/' -e 's/@[A-Z]*@//' \
  "$root/tests/cli/tiny_scene.toml" > tiny.toml
cat > sixteen.toml <<'EOT'
scene = "tiny.toml"
width = 96
height = 72
[[viewpoints]]
kind = "flowers"
count = 4
[sun]
angles = [[90.0, 20.0], [150.0, 45.0], [210.0, 45.0], [270.0, 20.0]]
EOT
workers=$(nproc)
now() { date +%s.%N; }
report() {  # report NAME OUT START END
  python3 - "$@" "$workers" <<'PY'
import json, sys
name, out, start, end, workers = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5])
b = json.load(open(out + "/batch.json"))
n = len(b["tasks"])
wall = end - start
task = sum(t["seconds"] for t in b["tasks"])
print(f"{name:6s} {n} stills, {b['done']} done: wall {wall:.2f} s, {60 * n / wall:.1f} stills/min, "
      f"mean task {task / n:.3f} s, overhead {(wall * workers - task) / n:.3f} s/still ({workers} workers)")
PY
}
t0=$(now); "$bin" --quiet build tiny.toml --out one-build > /dev/null; t1=$(now)
echo "one scene build (placement + POV-Ray files): $(echo "$t1 - $t0" | bc) s"
t0=$(now); "$bin" --quiet batch run sixteen.toml --out local --workers "$workers"; t1=$(now)
report local local "$t0" "$t1"
t0=$(now); "$bin" --quiet batch run sixteen.toml --out local --workers "$workers"; t1=$(now)
echo "rerun (all 16 skipped): $(echo "$t1 - $t0" | bc) s"
if [ "$(id -u)" -eq 0 ] && command -v slurmctld > /dev/null; then
  . "$root/tests/cli/batch/slurm_cluster.sh"
  trap stop_slurm_cluster EXIT
  t0=$(now); start_slurm_cluster "$scratch/cluster" 2> cluster.log; t1=$(now)
  echo "slurm cluster up (munged, slurmctld, slurmd, node idle): $(echo "$t1 - $t0" | bc) s"
  for chunk in 1 4; do
    t0=$(now); "$bin" --quiet batch run sixteen.toml --out "slurm$chunk" --executor slurm --chunk $chunk; t1=$(now)
    report "slurm --chunk $chunk" "slurm$chunk" "$t0" "$t1"
  done
  for f in local/stills/*.png; do cmp -s "$f" "slurm1/stills/${f##*/}" || echo "DIFFERS: $f"; done
fi
