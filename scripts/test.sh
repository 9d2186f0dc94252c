#!/usr/bin/env bash
# Quick start 2: install, build, and run the whole test suite (CTest prints its summary).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/build.sh
ctest --preset release "$@"
