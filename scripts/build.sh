#!/usr/bin/env bash
# Installs the Debian packages (idempotent), configures and builds the release preset: all of it
# (the program, the tests and the benchmarks), or with --demo the program alone, with only the
# packages it needs (scripts/debian-packages.txt marks them).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
if [ "${1:-}" = --demo ]; then
  bash scripts/install-deps.sh --demo
  cmake --preset release -DWANGSCAPE_BUILD_TESTS=OFF -DWANGSCAPE_BUILD_BENCH=OFF >/dev/null
  cmake --build --preset release --target wangscape
else
  bash scripts/install-deps.sh
  cmake --preset release -DWANGSCAPE_BUILD_TESTS=ON -DWANGSCAPE_BUILD_BENCH=ON >/dev/null
  cmake --build --preset release
fi
