#!/bin/sh
# architecture_check.sh SOURCE_DIR: every #include "folder/..." in a library folder must point to
# the folder itself or to one it may depend on (docs/architecture.md); renders/ is checked room by
# room (renders/trace, renders/ldi, ...), and the third-party libraries that make a room heavy
# (Embree, SDL2) may be linked only where the design puts them; the view library and the window
# print nothing and name no flag (only cli/ does); only folder/ names a scene folder's files.
# Prints each wrong arrow.
cd "$1" || exit 2
below_scene="core generator terrain templates scene"
allowed() {
  case "$1" in
    core) echo "core" ;;
    generator | terrain | templates) echo "core $1" ;;
    scene) echo "$below_scene" ;;
    exporters) echo "$below_scene exporters" ;;
    folder) echo "$below_scene exporters folder" ;;
    renders/trace) echo "$below_scene renders/trace" ;;
    renders/ldi) echo "$below_scene exporters folder renders/trace renders/ldi" ;;
    renders/external) echo "core templates exporters folder renders/external" ;;
    renders/view) echo "$below_scene exporters folder renders/trace renders/ldi renders/view" ;;
    renders/window) echo "core exporters folder renders/view renders/window" ;;
    renders/batch) echo "$below_scene exporters folder renders/external renders/batch" ;;
    renders) echo "$below_scene exporters folder renders/trace renders/ldi renders/external renders" ;;
  esac
}
# The unit an include or a file belongs to: its folder, or its room of renders/.
unit_of() {
  case "$1" in
    renders/*/*) echo "$1" | cut -d/ -f1-2 ;;
    *) echo "$1" | cut -d/ -f1 ;;
  esac
}
status=0
for file in $(find core generator terrain templates scene exporters folder renders -name '*.h' -o -name '*.cpp'); do
  folder=$(unit_of "$file")
  ok=$(allowed "$folder")
  [ -n "$ok" ] || { echo "$file: $folder is not a folder or room of docs/architecture.md"; status=1; continue; }
  for included in $(sed -n 's/^#include "\([a-z_]*\/[a-z_/]*\)\.h".*/\1/p' "$file" | sort -u); do
    target=$(unit_of "$included")
    case " $ok " in
      *" $target "*) ;;
      *) echo "$file includes $target/: $folder/ may use only: $ok"; status=1 ;;
    esac
  done
done
# The pack format reads and writes bytes: no Embree, nothing but core/ and the pack itself.
for file in folder/ldi.h folder/ldi_pack.h folder/ldi_pack.cpp folder/ldi_info.h folder/ldi_info.cpp; do
  if grep -q '^#include <embree' "$file" || grep '^#include "' "$file" | grep -qv '"core/\|"folder/ldi'; then
    echo "$file: the LDI pack format uses only core/ (no Embree, no scene, no exporters)"; status=1
  fi
done
# A scene folder's files are named in folder/ only (folder/folder_files.h); readers ask it. The
# POV-Ray export's entry is its writer's (exporters/povray_writer.h), which the folder refers to.
names='"(scene\.toml|scene_base\.txt|scene\.cache|tiles\.json|tiles\.ldi|steep\.ldi|sky\.bin|ground_light\.bin|scene\.glb|plants\.gpkg|cover\.tif|scene\.pov)"'
for file in $(find core generator terrain templates scene exporters renders cli -name '*.h' -o -name '*.cpp'); do
  case "$file" in exporters/povray_writer.h) continue ;; esac
  for line in $(sed 's|//.*||' "$file" | grep -nE "$names" | cut -d: -f1); do
    echo "$file:$line: names a scene folder's file: only folder/ may (ask FolderFiles, folder/folder_files.h)"; status=1
  done
done
# SDL2 only in the window; Embree only in trace, ldi and view.
for cmake in $(find core generator terrain templates scene exporters folder renders cli -name CMakeLists.txt); do
  case "$cmake" in renders/window/*) ;; *)
    grep -q 'SDL2::' "$cmake" && { echo "$cmake links SDL2: only renders/window/ may"; status=1; } ;;
  esac
  case "$cmake" in renders/trace/* | renders/ldi/* | renders/view/*) ;; *)
    grep -q '[ (]embree[ )]' "$cmake" && { echo "$cmake links Embree: only renders/trace, ldi and view may"; status=1; } ;;
  esac
done
# The view library and the window are typed APIs: no print to stdout or stderr and no flag's name
# ("--fov") in a string literal outside comments. The program (cli/) parses the flags, words the
# messages that name them and prints progress, figures and what it wrote.
prints='(^|[^a-z_])(printf|puts|fputs|fputc|putchar|perror)[[:space:]]*\(|std::(cout|cerr|clog)|(^|[^a-zA-Z_])(stdout|stderr)([^a-zA-Z_]|$)'
for file in $(find renders/view renders/window -name '*.h' -o -name '*.cpp'); do
  code=$(sed 's|//.*||' "$file")
  for line in $(printf '%s\n' "$code" | grep -nE "$prints" | cut -d: -f1); do
    echo "$file:$line: prints: only cli/ may (report through a callback or a return value)"; status=1
  done
  for line in $(printf '%s\n' "$code" | grep -no '"\([^"\\]\|\\.\)*"' | grep -- '--[a-zA-Z]' | cut -d: -f1 | sort -u); do
    echo "$file:$line: names a flag: only cli/ may (take the name as a parameter, or let cli/ check first)"; status=1
  done
done
[ "$status" -eq 0 ] && echo "architecture: every include and link follows docs/architecture.md; renders/view and renders/window print nothing and name no flag; only folder/ names a scene folder's files"
exit "$status"
