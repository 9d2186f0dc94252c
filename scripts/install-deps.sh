#!/usr/bin/env bash
# Installs every Debian package in scripts/debian-packages.txt (idempotent: installs only
# what is missing), then the npm tools the tests use into tools/node_modules. With --demo, only
# the packages marked "demo" there (the program and POV-Ray) and no npm tools.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
demo_only=false
[ "${1:-}" = --demo ] && demo_only=true

if $demo_only; then
  mapfile -t wanted < <(grep -v '^\s*#' "$here/debian-packages.txt" | awk 'NF && $2 == "demo" {print $1}')
else
  mapfile -t wanted < <(grep -v '^\s*#' "$here/debian-packages.txt" | awk 'NF{print $1}')
fi
missing=()
for pkg in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' || missing+=("$pkg")
done

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${#missing[@]} Debian packages: ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "install-deps: all ${#wanted[@]} Debian packages present"
fi

$demo_only && exit 0

# Node and npm: the machine image may already carry a newer Node with npm; Debian's
# npm package conflicts with that, so install Debian's only when npm is missing.
if ! command -v npm >/dev/null 2>&1; then
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
fi

# npm tooling (the Khronos glTF validator), pinned in tools/package.json.
if [ -f "$root/tools/package.json" ] && [ ! -d "$root/tools/node_modules" ]; then
  echo "install-deps: installing npm tools into tools/node_modules"
  (cd "$root/tools" && npm install --no-audit --no-fund --silent)
fi
