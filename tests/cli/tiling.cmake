# wangscape tileset / tiling, run for real: output shapes, files, exit codes, no partial files.
# The checks live in tiling/check.cmake (one MODE per test).
foreach(mode IN ITEMS tileset_json tileset_sheet tiling_outputs hash_window stats_json aperiodic usage_errors
                      runtime_errors)
  add_test(NAME cli_tiling_${mode}
    COMMAND ${CMAKE_COMMAND} -DBIN=${WANGSCAPE_BIN} -DSCRATCH=${CLI_SCRATCH}/tiling_${mode} -DMODE=${mode}
            -P ${CMAKE_CURRENT_LIST_DIR}/tiling/check.cmake)
  set_tests_properties(cli_tiling_${mode} PROPERTIES LABELS cli TIMEOUT 120)
endforeach()
