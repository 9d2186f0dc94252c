# One voice for output (issue 24): each command family says what it wrote in one line on stderr,
# nothing under --quiet, exit codes 0 and 1 (tests/cli/output/voice.sh, one FAMILY per test).
foreach(family IN ITEMS tileset tiling tiles scene ldi)
  add_test(NAME cli_output_${family}
    COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/output/voice.sh ${WANGSCAPE_BIN} ${PROJECT_SOURCE_DIR}
            ${CLI_SCRATCH}/output_${family} ${family})
  set_tests_properties(cli_output_${family} PROPERTIES LABELS cli TIMEOUT 120)
endforeach()
