#!/bin/sh
# bench/no_identical_neighbours_bench.sh [WANGSCAPE]: the periodicity score (`tiling --json`,
# generator/tiling_stats.h) with and without --no-identical-neighbours, averaged over SEEDS seeds,
# for each set in SETS, algorithm in ALGORITHMS and size in SIZES (issue 23, item 3). A score is
# mostly noise below 64 x 64 (about 0.07 at 32 x 32 for any stochastic tiling); compare means.
#   sh bench/no_identical_neighbours_bench.sh
#   SETS="cohen8" SIZES="256" SEEDS=5 sh bench/no_identical_neighbours_bench.sh
set -eu
bin=${1:-build/release/cli/wangscape}
sets=${SETS:-cohen8 cohen12 cohen18 owen12 complete-edge-2 corner-2}
algorithms=${ALGORITHMS:-scanline bottom-left}
sizes=${SIZES:-32 64 128}
seeds=${SEEDS:-10}
uptime
mean() {  # SET ALGORITHM SIZE [FLAG]
  total=0
  seed=1
  while [ "$seed" -le "$seeds" ]; do
    score=$("$bin" tiling --set "$1" --algorithm "$2" --size "$3x$3" --seed "$seed" --json ${4:-} |
      sed -n 's/^ *"periodicity": *\([0-9.eE+-]*\),*$/\1/p')
    total=$(awk -v a="$total" -v b="$score" 'BEGIN { printf "%.6f", a + b }')
    seed=$((seed + 1))
  done
  awk -v a="$total" -v n="$seeds" 'BEGIN { printf "%.4f", a / n }'
}
printf '%-16s %-12s %5s  %-8s %-8s\n' set algorithm size plain forbid
for set in $sets; do
  for algorithm in $algorithms; do
    for size in $sizes; do
      printf '%-16s %-12s %5s  %-8s %-8s\n' "$set" "$algorithm" "$size" "$(mean "$set" "$algorithm" "$size")" \
        "$(mean "$set" "$algorithm" "$size" --no-identical-neighbours)"
    done
  done
done
uptime
