# wangscape ldi build / info / sheet, run for real on a tiny flat field (1 level, 2 directions,
# small flowers), and their refusals: exit codes are checked by terrain/expect.cmake (CTest
# ignores them when PASS_REGULAR_EXPRESSION is set).
set(ldi_dir "${CLI_SCRATCH}/ldi")
file(MAKE_DIRECTORY "${ldi_dir}")
file(WRITE "${ldi_dir}/tiny.toml" [=[
name = "ldi tiny"
[terrain]
flat_size = 60.0
[tiles]
set = "cohen8"
tile_size = 4.0
points_per_tile = 6
seed = 5
area = [-12.0, -12.0, 12.0, 12.0]
[models]
variants = 3
triangle_budget = 400
[sun]
azimuth = 200.0
elevation = 40.0
]=])
file(WRITE "${ldi_dir}/short.ldi" "WSCLDI\r\n too short to be a pack")

# ldi_cli_test(NAME CODE ARGS [OUT regex] [ERR regex] [NO_FILE path]): ARGS separated by '|'.
function(ldi_cli_test name code args)
  cmake_parse_arguments(T "" "OUT;ERR;NO_FILE;SETUP;REQUIRES" "" ${ARGN})
  set(defs -DBIN=${WANGSCAPE_BIN} -DCODE=${code} "-DARGS=${args}")
  foreach(key OUT ERR NO_FILE)
    if(DEFINED T_${key})
      list(APPEND defs "-D${key}=${T_${key}}")
    endif()
  endforeach()
  add_test(NAME cli_ldi_${name}
           COMMAND ${CMAKE_COMMAND} ${defs} -P ${CMAKE_CURRENT_LIST_DIR}/terrain/expect.cmake)
  set_tests_properties(cli_ldi_${name} PROPERTIES LABELS "cli;ldi" TIMEOUT 300)
  if(DEFINED T_SETUP)
    set_tests_properties(cli_ldi_${name} PROPERTIES FIXTURES_SETUP ${T_SETUP})
  endif()
  if(DEFINED T_REQUIRES)
    set_tests_properties(cli_ldi_${name} PROPERTIES FIXTURES_REQUIRED ${T_REQUIRES})
  endif()
endfunction()

ldi_cli_test(build 0
  "--quiet|ldi|build|${ldi_dir}/tiny.toml|--out|${ldi_dir}/tiny.ldi|--levels|1|--directions|2|--sky-rays|1"
  ERR "^$" SETUP ldi_pack)
ldi_cli_test(info_json 0 "ldi|info|--json|${ldi_dir}/tiny.ldi"
  OUT "^{\"tiles\":8,\"levels\":1,\"directions\":2,\"resolutions\":\\[4[0-9][0-9]\\],\"depth_pixels\":[1-9][0-9]*,\"bytes\":[1-9][0-9]*,"
  REQUIRES ldi_pack)
ldi_cli_test(info_text 0 "ldi|info|${ldi_dir}/tiny.ldi"
  OUT "tiles: +8\nlevels: +1\ndirections: +2\n.*layers per pixel \\(pixels\\): 0:[0-9]+, 1:[0-9]+.*depth pixels: [1-9]"
  REQUIRES ldi_pack)
ldi_cli_test(sheet 0 "ldi|sheet|${ldi_dir}/tiny.ldi|--tile|3|--cell|32|--out|${ldi_dir}/sheet.png"
  ERR "^wangscape: wrote [^\n]*sheet\\.png \\(tile 3, [0-9.]+ [kM]?B\\) in [0-9.]+ s\n$" REQUIRES ldi_pack)
ldi_cli_test(sheet_no_such_tile 1 "ldi|sheet|${ldi_dir}/tiny.ldi|--tile|8|--out|${ldi_dir}/sheet8.png"
  ERR "^wangscape: error: [^\n]*tiny\\.ldi: no tile 8 \\(the pack has 8\\)" NO_FILE "${ldi_dir}/sheet8.png"
  REQUIRES ldi_pack)
ldi_cli_test(info_not_a_pack 1 "ldi|info|${ldi_dir}/tiny.toml"
  ERR "^wangscape: error: [^\n]*tiny\\.toml: bad magic: not a Wangscape LDI pack")
ldi_cli_test(info_truncated 1 "ldi|info|${ldi_dir}/short.ldi"
  ERR "^wangscape: error: [^\n]*short\\.ldi: truncated: [0-9]+ bytes, shorter than the 64-byte header")
ldi_cli_test(info_missing 1 "ldi|info|${ldi_dir}/no_such.ldi" ERR "^wangscape: error: [^\n]*no_such\\.ldi: cannot open")
ldi_cli_test(build_missing_scene 1 "--quiet|ldi|build|${ldi_dir}/no_such.toml|--out|${ldi_dir}/none.ldi"
  ERR "^wangscape: error: [^\n]*no_such\\.toml" NO_FILE "${ldi_dir}/none.ldi")
ldi_cli_test(build_needs_out 2 "ldi|build|${ldi_dir}/tiny.toml" ERR "--out")
ldi_cli_test(build_bad_ground 2 "ldi|build|${ldi_dir}/tiny.toml|--out|${ldi_dir}/x.ldi|--ground|sky" ERR "ground")

# [exports] ldi = true: `wangscape build` writes DIR/tiles.ldi with the view of the [ldi] section.
file(READ "${ldi_dir}/tiny.toml" ldi_export_text)
file(WRITE "${ldi_dir}/export.toml" "${ldi_export_text}[exports]\nldi = true\n[ldi]\nlevels = 2\ndirections = 2\nsky_rays = 0\n")
add_test(NAME cli_ldi_build_export
  COMMAND ${cli_expect} 0 "\"levels\": *2, *\"directions\": *2"
          sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && test -s \"$1/scene.pov\" && \"$0\" ldi info --json \"$1/tiles.ldi\""
          "${WANGSCAPE_BIN}" "${ldi_dir}/export")
set_tests_properties(cli_ldi_build_export PROPERTIES LABELS "cli;ldi" TIMEOUT 300)
