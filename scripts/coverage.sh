#!/usr/bin/env bash
# Line and function coverage of the library code by the sanitizer run's test selection (the test
# presets asan-tests and coverage-tests share it: CMakePresets.json, library-tests). Builds the
# GoogleTest programs with gcov (coverage preset, -O0), runs the selection, and prints gcovr's
# summary over the libraries (tests/ and cli/ left out); the per-file table goes to
# build/coverage/coverage.txt. Counters bumped by several threads at once can make a branch
# count negative, which gcovr 5.2 calls a parse error: those lines are skipped, not the run.
# Extra arguments go to ctest (-E '^cli_' runs every library test).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset coverage >/dev/null
cmake --build --preset coverage-tests -j 2
find build/coverage -name '*.gcda' -delete
ctest --preset coverage-tests "$@"
gcovr --root . --filter '(core|generator|terrain|templates|scene|exporters|renders)/' -j 2 --gcov-ignore-parse-errors \
  --txt build/coverage/coverage.txt --print-summary build/coverage
