# wangscape terrain info, run for real on the test DEMs (tests/data/dem) and their edge cases.
set(_terrain_dem "${PROJECT_SOURCE_DIR}/tests/data/dem")

# terrain_cli_test(NAME CODE ARGS [OUT regex] [ERR regex]): ARGS separated by '|'.
function(terrain_cli_test name code args)
  cmake_parse_arguments(T "" "OUT;ERR;NO_FILE" "" ${ARGN})
  set(defs -DBIN=${WANGSCAPE_BIN} -DCODE=${code} "-DARGS=${args}")
  if(DEFINED T_OUT)
    list(APPEND defs "-DOUT=${T_OUT}")
  endif()
  if(DEFINED T_ERR)
    list(APPEND defs "-DERR=${T_ERR}")
  endif()
  if(DEFINED T_NO_FILE)
    list(APPEND defs "-DNO_FILE=${T_NO_FILE}")
  endif()
  add_test(NAME cli_terrain_${name} COMMAND ${CMAKE_COMMAND} ${defs} -P ${CMAKE_CURRENT_LIST_DIR}/terrain/expect.cmake)
  set_tests_properties(cli_terrain_${name} PROPERTIES LABELS "cli;terrain" TIMEOUT 120)
endfunction()

terrain_cli_test(info_sainte_helens 0 "terrain|info|${PROJECT_SOURCE_DIR}/data/SainteHelens.dem"
  OUT "crs: [^\n]*projected.*datum: +NAD27.*size: +327 x 468 samples.*spacing: +30 x 30 m.*heights: +682\\.00 \\.\\. 2543\\.00 m.*no-data cells: +4151 of 153036.*origin: +lat 46\\.18[0-9]+, lon -122\\.18[0-9]+.*utm zone: +10N.*convergence: +0\\.58[0-9]+ deg.*datum note: +NAD27 -> WGS 84[^\n]*accurate to about"
  ERR "^$")
terrain_cli_test(info_embedded_default 0 "terrain|info|${PROJECT_SOURCE_DIR}/data/SainteHelens.dem"
  OUT "size: +327 x 468 samples.*heights: +682\\.00 \\.\\. 2543\\.00 m")
terrain_cli_test(info_json 0 "terrain|info|--json|${PROJECT_SOURCE_DIR}/data/SainteHelens.dem"
  OUT "\"width\": 327,.*\"height\": 468,.*\"min_height_m\": 682\\.0,.*\"max_height_m\": 2543\\.0,.*\"nodata_count\": 4151,.*\"utm_zone\": 10,.*\"source_crs_wkt\": \"PROJCRS")
terrain_cli_test(info_boulder 0 "terrain|info|${_terrain_dem}/SRTMGL3_boulder_CO_240x144.asc"
  OUT "crs: [^\n]*geographic.*size: +240 x 144 samples.*heights: +1943\\.00 \\.\\. 3286\\.00 m.*no-data cells: +0 of 34560.*utm zone: +13N.*datum note: +WGS 84 geographic already")
terrain_cli_test(info_origin 0 "terrain|info|--origin|46.2,-122.2|${PROJECT_SOURCE_DIR}/data/SainteHelens.dem"
  OUT "origin: +lat 46\\.20000000, lon -122\\.20000000")
terrain_cli_test(info_edge_39109h1 0 "terrain|info|${_terrain_dem}/edge-cases/39109h1_truncated.dem"
  OUT "size: +2 x 1411 samples.*heights: +1687\\.4[0-9] \\.\\. 1716\\.9[0-9] m.*utm zone: +12N")
terrain_cli_test(info_edge_39079G6 0 "terrain|info|${_terrain_dem}/edge-cases/39079G6_truncated.dem"
  OUT "datum: +WGS 72.*size: +2 x 470 samples.*heights: +325\\.00 \\.\\. 385\\.00 m.*datum note: +WGS 72 -> WGS 84")
terrain_cli_test(info_edge_cded_all_nodata 1 "terrain|info|${_terrain_dem}/edge-cases/114p01_0100_deme_truncated.dem"
  ERR "^wangscape: error: DEM '[^']*114p01_0100_deme_truncated\\.dem' has no valid heights")
terrain_cli_test(info_edge_fema_no_profiles 1 "terrain|info|${_terrain_dem}/edge-cases/fema06-140cm_2995441b_truncated.dem"
  ERR "^wangscape: error: DEM '[^']*fema06-140cm_2995441b_truncated\\.dem': the header declares 2129 x 2797 cells but its elevation profiles cannot be read")
terrain_cli_test(info_missing_file 1 "terrain|info|${CLI_SCRATCH}/no_such.dem"
  ERR "^wangscape: error: DEM file '[^']*no_such\\.dem' does not exist")
terrain_cli_test(info_not_a_dem 1 "terrain|info|${PROJECT_SOURCE_DIR}/data/README.md"
  ERR "README\\.md': not a raster format GDAL recognizes")
terrain_cli_test(info_no_file 2 "terrain|info")
terrain_cli_test(info_bad_origin 2 "terrain|info|--origin|95,0|${PROJECT_SOURCE_DIR}/data/SainteHelens.dem" ERR "LAT,LON")
terrain_cli_test(info_unknown_option 2 "terrain|info|--bogus|${PROJECT_SOURCE_DIR}/data/SainteHelens.dem")
terrain_cli_test(no_subcommand 2 "terrain")

# wangscape terrain height: the ground under points of the scene frame (issue 24). The default
# scene's frame (the DEM's center): 0,6590 is the pumice plain at 1117.89 m; its lat/lon gives the
# same point; the DEM's south-west corner holds no-data; beyond the DEM is refused.
set(_helens "${PROJECT_SOURCE_DIR}/data/SainteHelens.dem")
terrain_cli_test(height_point 0 "terrain|height|${_helens}|0,6590" OUT "^0\\.00,6590\\.00,1117\\.89\n$" ERR "^$")
terrain_cli_test(height_points_above 0 "terrain|height|${_helens}|0,6590|-200,6000|--above|1.7"
  OUT "^0\\.00,6590\\.00,1119\\.59\n-200\\.00,6000\\.00,1143\\.87\n$")
terrain_cli_test(height_latlon 0 "terrain|height|${_helens}|--latlon|46.24659967532685,-122.18859025851513"
  OUT "^0\\.00,6590\\.00,1117\\.89\n$")
terrain_cli_test(height_origin 0 "terrain|height|${_helens}|--origin|46.24659967532685,-122.18859025851513|0,0"
  OUT "^0\\.00,0\\.00,1117\\.89\n$")
terrain_cli_test(height_json 0 "terrain|height|${_helens}|0,6590|--above|2|--json"
  OUT "\"east_m\": 0\\.0,.*\"ground_m\": 1117\\.89[0-9]*,.*\"latitude_deg\": 46\\.2465[0-9]*,.*\"longitude_deg\": -122\\.1885[0-9]*,.*\"north_m\": 6590\\.0,.*\"position_m\": .*1119\\.89")
terrain_cli_test(height_nodata 1 "terrain|height|${_helens}|-4830,-6900"
  ERR "^wangscape: error: SainteHelens\\.dem \\(327 x 468 samples, 30 m\\) has no height at east -4830 m, north -6900 m: a corner of the DEM cell there holds the no-data value\n$")
terrain_cli_test(height_outside 1 "terrain|height|${_helens}|0,6590|90000,0" OUT "^$"
  ERR "^wangscape: error: east 90000 m, north 0 m is outside SainteHelens\\.dem \\(327 x 468 samples, 30 m\\), which spans east -4837 \\.\\. 4823 m, north -6947 \\.\\. 6947 m\n$")
terrain_cli_test(height_off_grid 1 "terrain|height|${_helens}|-4830,6900" ERR "is off the grid of SainteHelens\\.dem")
terrain_cli_test(height_no_point 2 "terrain|height|${_helens}" ERR "at least one point")
terrain_cli_test(height_bad_point 2 "terrain|height|${_helens}|1,2,3" ERR "'1,2,3' is not E,N in meters")
terrain_cli_test(height_bad_latlon 2 "terrain|height|${_helens}|--latlon|95,0" ERR "LAT,LON")
add_test(NAME cli_terrain_height_folder
  COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/terrain/height_folder.sh ${WANGSCAPE_BIN} ${CLI_SCRATCH}/terrain_height_folder ${_helens}
          ${PROJECT_SOURCE_DIR})
set_tests_properties(cli_terrain_height_folder PROPERTIES LABELS "cli;terrain" TIMEOUT 120)

# wangscape scatter --dem (tests/cli/terrain/scatter_check.cmake, one MODE per test).
foreach(mode IN ITEMS below_threshold explained_empty errors)
  add_test(NAME cli_terrain_scatter_${mode}
    COMMAND ${CMAKE_COMMAND} -DBIN=${WANGSCAPE_BIN} -DSCRATCH=${CLI_SCRATCH}/terrain_scatter_${mode}
            -DDEM=${PROJECT_SOURCE_DIR}/data/SainteHelens.dem -DMODE=${mode}
            -P ${CMAKE_CURRENT_LIST_DIR}/terrain/scatter_check.cmake)
  set_tests_properties(cli_terrain_scatter_${mode} PROPERTIES LABELS "cli;terrain" TIMEOUT 300)
endforeach()
