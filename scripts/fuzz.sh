#!/usr/bin/env bash
# Builds the fuzz preset (clang, libFuzzer, ASan + UBSan: fuzz/) and runs each fuzzer for a short
# while over its seed corpus (the CTests fuzz_*: a fixed seed and number of executions, about 10 s each). Extra arguments go to ctest. A
# finding fails its test and is left in build/fuzz/fuzz/work/<name>/ (crash-*, leak-*, timeout-*).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j 2
ctest --preset fuzz "$@"
