#!/usr/bin/env bash
# bench/fuzz_million.sh [NAME...]: runs each fuzzer of fuzz/ (default: all nine) for 10^6
# executions (RUNS to change it) from its seed corpus, one after the other, and prints per
# fuzzer: executions per second, wall time, peak RSS, corpus size reached and findings. The
# corpus grows in a scratch folder; findings (crash-*, leak-*, timeout-*, oom-*) are kept in
# build/fuzz/fuzz/million/<name>/ (OUT=DIR to change, so that two runs can go side by side) for
# reproducing: build/fuzz/fuzz/<name>_fuzz FILE.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
runs=${RUNS:-1000000}
[ $# -gt 0 ] || set -- scene_file tileset filled_tileset dem ldi_pack batch_file batch_plan view_path model_file
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j 2 >/dev/null
bin="$root/build/fuzz/fuzz"
out=${OUT:-$bin/million}  # where findings and logs go
echo "load before: $(uptime | sed 's/.*load/load/')"
printf '%-16s %10s %9s %9s %8s %9s  %s\n' fuzzer executions exec/s wall_s rss_mb corpus findings
status=0
for name in "$@"; do
  work=$(mktemp -d)
  mkdir -p "$out/$name"
  cp -r "fuzz/corpus/$name/." "$work/"
  rm -f "$work/README.md"
  dict=""
  case "$name" in
    scene_file) dict="-dict=fuzz/dict/scene_file.dict" ;;
    tileset | filled_tileset) dict="-dict=fuzz/dict/tileset.dict" ;;
    batch_file) dict="-dict=fuzz/dict/batch_file.dict" ;;
    # Assimp's own faults are expected here (fuzz/CMakeLists.txt); its leaks are suppressed.
    model_file) dict="-dict=fuzz/dict/model_file.dict"
      export LSAN_OPTIONS="suppressions=$root/fuzz/model_file.lsan" ;;
  esac
  start=$(date +%s.%N)
  code=0
  "$bin/${name}_fuzz" -runs="$runs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    $dict -artifact_prefix="$out/$name/" "$work" > "$out/$name/log.txt" 2>&1 || code=$?
  end=$(date +%s.%N)
  stat() { sed -n "s/^stat::$1: *//p" "$out/$name/log.txt" | tail -n 1; }
  findings=$(find "$out/$name" -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' | wc -l)
  verdict="none"
  if [ "$code" -ne 0 ] || [ "$findings" -gt 0 ]; then
    verdict="exit $code, $findings file(s) in $out/$name/ (see log.txt)"
    status=1
  fi
  printf '%-16s %10s %9s %9.1f %8s %9s  %s\n' "$name" "$(stat number_of_executed_units)" \
    "$(stat average_exec_per_sec)" "$(awk "BEGIN { print $end - $start }")" "$(stat peak_rss_mb)" \
    "$(find "$work" -type f | wc -l)" "$verdict"
  rm -rf "$work"
done
echo "load after: $(uptime | sed 's/.*load/load/')"
exit "$status"
