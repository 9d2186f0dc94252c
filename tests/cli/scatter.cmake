# wangscape tileset --per-tile / scatter, run for real (issue 3): the filled set's JSON, CSV and
# PLY instances with no pair closer than the packing diameter, metrics, exit codes, no partial
# files; streams: no count cap over a DEM, --max-instances, the disk and memory checks (issue 24).
# The checks live in scatter/check.sh (one MODE per test; python3 reads the outputs).
foreach(mode IN ITEMS fill csv ply metrics hash deterministic errors streams)
  add_test(NAME cli_scatter_${mode}
    COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/scatter/check.sh ${WANGSCAPE_BIN} ${CLI_SCRATCH}/scatter_${mode} ${mode}
            ${PROJECT_SOURCE_DIR}/data/SainteHelens.dem)
  set_tests_properties(cli_scatter_${mode} PROPERTIES LABELS cli TIMEOUT 120)
endforeach()

# On a terminal (script(1) gives it one) the bar says, before the first byte, what the points
# file will hold: "of about N instances, SIZE" (issue 40: a README example once streamed 5 GB
# with a bar that said neither).
add_test(NAME cli_scatter_progress_on_a_terminal
  COMMAND ${cli_expect} 0 "scatter \\[.*of about [0-9.]+( million)? instances, [0-9.]+ (B|kB|MB)"
          sh -c "mkdir -p \"$1\" && \"$0\" --quiet tileset --set cohen8 --per-tile 5 --out \"$1/filled.json\" >/dev/null && exec script -qec \"'$0' scatter --tileset '$1/filled.json' --plane 600x600 --out '$1/p.csv'\" /dev/null"
          ${WANGSCAPE_BIN} ${CLI_SCRATCH}/scatter_progress)
set_tests_properties(cli_scatter_progress_on_a_terminal PROPERTIES LABELS cli TIMEOUT 120)
