#!/usr/bin/env bash
# Quick start 2: install, build, and run the whole test suite (CTest prints its summary), then the
# library tests under ASan and UBSan (scripts/sanitizers.sh; README, "Sanitizers and fuzzers").
# Extra arguments go to the release suite's ctest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/build.sh
ctest --preset release "$@"
bash scripts/sanitizers.sh
