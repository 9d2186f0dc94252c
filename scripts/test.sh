#!/usr/bin/env bash
# Quick start 2: install, build, and run the whole test suite (CTest prints its summary), then the
# library tests under ASan and UBSan (scripts/sanitizers.sh; README, "Sanitizers and fuzzers").
# A compiler warning fails it too (CI runs this on a clean clone, so every file is compiled).
# Extra arguments go to the release suite's ctest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
build_log=$(mktemp)
trap 'rm -f "$build_log"' EXIT
bash scripts/build.sh 2>&1 | tee "$build_log"
if grep -Eq "^[^ ]+:[0-9]+:([0-9]+:)? warning:" "$build_log"; then
  echo "scripts/test.sh: the build printed compiler warnings (above); a build must print none" >&2
  exit 1
fi
ctest --preset release "$@"
bash scripts/sanitizers.sh
