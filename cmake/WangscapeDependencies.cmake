# Every dependency comes from Debian packages (scripts/debian-packages.txt); nothing is
# downloaded at configure or build time.
find_package(TBB REQUIRED)
find_package(Threads REQUIRED)

if(WANGSCAPE_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()

if(WANGSCAPE_GENERATOR_ONLY)
  return()
endif()

find_package(CLI11 REQUIRED)
find_package(fmt REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(TOMLPLUSPLUS REQUIRED IMPORTED_TARGET tomlplusplus)
find_package(GDAL CONFIG REQUIRED)
find_package(embree 3 REQUIRED)
# Users' models (templates/mesh_io.cpp): Debian's libassimp-dev 5.2 exports assimp::assimp.
find_package(assimp REQUIRED)
# The stand-ins of users' models (templates/stand_in.cpp): Debian's libmeshoptimizer-dev 0.18,
# found as a header and a library.
find_path(MESHOPTIMIZER_INCLUDE_DIR meshoptimizer.h REQUIRED)
find_library(MESHOPTIMIZER_LIBRARY meshoptimizer REQUIRED)
add_library(wangscape_meshoptimizer INTERFACE IMPORTED)
target_include_directories(wangscape_meshoptimizer INTERFACE "${MESHOPTIMIZER_INCLUDE_DIR}")
target_link_libraries(wangscape_meshoptimizer INTERFACE "${MESHOPTIMIZER_LIBRARY}")
# The real-time view's window (renders/window/ldi_window.cpp); Debian's SDL2 exports SDL2::SDL2.
find_package(SDL2 REQUIRED)
if(WANGSCAPE_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# Debian's OpenImageIO target lists /usr/include/opencv4, which does not exist and makes
# generation fail: keep only the include directories that exist.
find_package(OpenImageIO CONFIG REQUIRED)
get_target_property(_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
set(_oiio_existing_includes "")
foreach(_dir IN LISTS _oiio_includes)
  if(EXISTS "${_dir}" OR _dir MATCHES "^\\$<")
    list(APPEND _oiio_existing_includes "${_dir}")
  endif()
endforeach()
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_existing_includes}")

# GeographicLib ships a Find module but no target: wrap its variables in one.
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
if(NOT TARGET GeographicLib::GeographicLib)
  add_library(GeographicLib::GeographicLib INTERFACE IMPORTED)
  set_target_properties(GeographicLib::GeographicLib PROPERTIES
    INTERFACE_LINK_LIBRARIES "${GeographicLib_LIBRARIES}"
    INTERFACE_INCLUDE_DIRECTORIES "${GeographicLib_INCLUDE_DIRS}")
endif()
