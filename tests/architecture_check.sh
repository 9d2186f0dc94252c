#!/bin/sh
# architecture_check.sh SOURCE_DIR: every #include "folder/..." in a library folder must point to
# the folder itself or to one it may depend on (docs/architecture.md). Prints each wrong arrow.
cd "$1" || exit 2
allowed() {
  case "$1" in
    core) echo "core" ;;
    generator | terrain | templates) echo "core $1" ;;
    scene) echo "core generator terrain templates scene" ;;
    exporters) echo "core generator terrain templates scene exporters" ;;
    renders) echo "core generator terrain templates scene exporters renders" ;;
  esac
}
status=0
for folder in core generator terrain templates scene exporters renders; do
  ok=$(allowed "$folder")
  for file in $(find "$folder" -name '*.h' -o -name '*.cpp'); do
    for target in $(sed -n 's/^#include "\([a-z_]*\)\/.*/\1/p' "$file" | sort -u); do
      case " $ok " in
        *" $target "*) ;;
        *) echo "$file includes $target/: $folder/ may use only: $ok"; status=1 ;;
      esac
    done
  done
done
[ "$status" -eq 0 ] && echo "architecture: every include follows docs/architecture.md"
exit "$status"
