#!/usr/bin/env bash
# Quick start 1: install, build, and run the main job on the embedded default scene.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/build.sh --demo  # the program alone, and only the packages it needs
exec ./build/release/cli/wangscape demo --out "${1:-out/demo}"
