# One INTERFACE target carries the warning flags every Wangscape target links.
add_library(wangscape_warnings INTERFACE)
target_compile_options(wangscape_warnings INTERFACE -Wall -Wextra -Wshadow)

# wangscape_add_library(NAME SOURCES...): a static library for one top-level folder,
# with the alias wangscape::NAME and the folder's parent on the include path, so code
# includes "generator/tileset.h".
# Each library is compiled as unity files (its sources joined, 8 to a file): the heavy headers
# (nlohmann-json, TBB, OIIO, GDAL) are then parsed once per 8 sources. A fresh build of the
# program went from 416 s of CPU to 211 s (README, "Quick start"). A source's
# anonymous namespace is then shared with its batch: two sources may not both define one name.
function(wangscape_add_library name)
  add_library(wangscape_${name} STATIC ${ARGN})
  set_target_properties(wangscape_${name} PROPERTIES UNITY_BUILD ON)
  add_library(wangscape::${name} ALIAS wangscape_${name})
  target_include_directories(wangscape_${name} PUBLIC "${PROJECT_SOURCE_DIR}")
  target_link_libraries(wangscape_${name} PRIVATE wangscape_warnings)
endfunction()
