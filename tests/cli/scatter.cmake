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
