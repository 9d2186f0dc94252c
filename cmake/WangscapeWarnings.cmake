# One INTERFACE target carries the warning flags every Wangscape target links.
add_library(wangscape_warnings INTERFACE)
target_compile_options(wangscape_warnings INTERFACE -Wall -Wextra -Wshadow)

# wangscape_add_library(NAME SOURCES...): a static library for one top-level folder,
# with the alias wangscape::NAME and the folder's parent on the include path, so code
# includes "generator/tileset.h".
function(wangscape_add_library name)
  add_library(wangscape_${name} STATIC ${ARGN})
  add_library(wangscape::${name} ALIAS wangscape_${name})
  target_include_directories(wangscape_${name} PUBLIC "${PROJECT_SOURCE_DIR}")
  target_link_libraries(wangscape_${name} PRIVATE wangscape_warnings)
endfunction()
