# Hostile input (issue 14): each case is refused with exit 1 (2 for flags) and a message that
# names the file or value, never a crash, a hang or a raw library text.
set(hostile_dir "${CLI_SCRATCH}/hostile")
file(MAKE_DIRECTORY "${hostile_dir}")
string(REPEAT ".a" 100000 hostile_dots)
file(WRITE "${hostile_dir}/deep.toml" "a${hostile_dots} = 1\n")
string(REPEAT "[" 100000 hostile_open)
string(REPEAT "]" 100000 hostile_close)
file(WRITE "${hostile_dir}/flat.toml" "[terrain]\nflat_size = 20.0\n[models]\nvariants = 1\ntriangle_budget = 400\n")
file(WRITE "${hostile_dir}/deep.json" "{\"name\": ${hostile_open}${hostile_close}, \"tiles\": []}\n")

# hostile_test(NAME CODE REGEX COMMAND...)
function(hostile_test name code regex)
  add_test(NAME hostile_${name} COMMAND ${cli_expect} ${code} "${regex}" ${ARGN})
  set_tests_properties(hostile_${name} PROPERTIES LABELS "cli;hostile" TIMEOUT 60)
endfunction()

hostile_test(deep_toml 1 "deep.toml:1: a key of more than 64 dotted parts"
             "${WANGSCAPE_BIN}" build "${hostile_dir}/deep.toml" --out "${hostile_dir}/out_deep")
hostile_test(deep_json 1 "deep.json:1: brackets nest deeper than 64"
             "${WANGSCAPE_BIN}" tiling --set "${hostile_dir}/deep.json" --size 4x4)
hostile_test(scene_from_dev_zero 1 "/dev/zero: the scene file is not a regular file"
             "${WANGSCAPE_BIN}" build /dev/zero --out "${hostile_dir}/out_zero")
hostile_test(tileset_from_dev_zero 1 "/dev/zero: the tile set is not a regular file"
             "${WANGSCAPE_BIN}" tiling --set /dev/zero --size 4x4)
hostile_test(dem_fifo 1 "is not a regular file"
             sh -c "rm -f \"$1\" && mkfifo \"$1\" && exec timeout 20 \"$0\" terrain info \"$1\""
             "${WANGSCAPE_BIN}" "${hostile_dir}/fifo.dem")
hostile_test(origin_overflow 1 "beyond tile coordinate \\+-2\\^60"
             "${WANGSCAPE_BIN}" tiling --set complete-edge-2 --algorithm hash
             --origin 9223372036854775807,9223372036854775807 --size 4x4 --out "${hostile_dir}/window.csv")
# scatter over a filled set made first
set(hostile_fill "\"$0\" --quiet tileset --set cohen8 --per-tile 5 --out \"$1/filled.json\" >/dev/null")
hostile_test(scatter_infinite_tile 1 "tile size inf m; expected a finite number"
             sh -c "${hostile_fill} && exec \"$0\" scatter --tileset \"$1/filled.json\" --tile-size inf --out \"$1/p.csv\""
             "${WANGSCAPE_BIN}" "${hostile_dir}")
hostile_test(scatter_tiny_tile 1 "beyond tile coordinate"
             sh -c "${hostile_fill} && exec \"$0\" scatter --tileset \"$1/filled.json\" --tile-size 1e-300 --out \"$1/p.csv\""
             "${WANGSCAPE_BIN}" "${hostile_dir}")
hostile_test(scatter_huge_plane 1 "the folder has [0-9.]+ [kMGTP]?B free"
             sh -c "${hostile_fill} && exec \"$0\" scatter --tileset \"$1/filled.json\" --plane 1e9x1e9 --out \"$1/p.csv\""
             "${WANGSCAPE_BIN}" "${hostile_dir}")
# A points file estimated above 1 GB (a README example once streamed 5 GB unasked) needs --yes;
# refused before the first byte, no file left.
# (0: scatter failed and left no file; CMake lists split at semicolons, so no ';' in the script.)
hostile_test(scatter_large_file_needs_yes 0 "would hold about 2.5e.07 instances, about 1.35 GB .*add --yes"
             sh -c "${hostile_fill} && rm -f \"$1/large.csv\" && \"$0\" scatter --tileset \"$1/filled.json\" --plane 10000x10000 --out \"$1/large.csv\" || exec test ! -e \"$1/large.csv\""
             "${WANGSCAPE_BIN}" "${hostile_dir}")
hostile_test(seed_negative 2 "'-1' is not a seed"
             "${WANGSCAPE_BIN}" tiling --set cohen8 --size 4x4 --seed -1)
hostile_test(seed_too_large 2 "is not a seed"
             "${WANGSCAPE_BIN}" tiling --set cohen8 --size 4x4 --seed 99999999999999999999)
hostile_test(max_height_nan 2 "'nan' is not a finite number"
             "${WANGSCAPE_BIN}" scatter --tileset "${hostile_dir}/filled.json" --dem "${PROJECT_SOURCE_DIR}/data/SainteHelens.dem" --max-height nan)
hostile_test(empty_out 1 "the output folder is empty"  # sh passes the empty word CMake would drop
             sh -c "exec \"$0\" build \"$1\" --out ''" "${WANGSCAPE_BIN}" "${hostile_dir}/flat.toml")
