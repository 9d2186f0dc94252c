#!/usr/bin/env bash
# The library tests under AddressSanitizer and UndefinedBehaviorSanitizer, as scripts/test.sh runs
# them after the release suite: configures the asan preset (-Og: half the compile time of -O1, so
# the build and the run fit the suite's budget), builds only the GoogleTest programs (build preset
# asan-tests) and runs the chosen tests (test preset asan-tests: the library tests less the slow
# statistical ones, the repeats of one scene and those that run POV-Ray or Blender; README,
# "Sanitizers and fuzzers"). Extra arguments go to ctest. The first report of either sanitizer,
# or a leak, fails its test.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset asan >/dev/null
cmake --build --preset asan-tests -j 2
ctest --preset asan-tests "$@"
