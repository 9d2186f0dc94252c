# Durable publishing (issue 41): a build with every export (twice: a new folder, then the swap),
# a scatter and a one-still batch under strace; durable_check.py asserts from the trace that each
# published file was flushed before its rename and each folder after (docs/scene-folder.md).
add_test(NAME cli_durable_publish
  COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/durable_publish.sh" "${WANGSCAPE_BIN}" "${CLI_SCRATCH}/durable"
          "${CMAKE_CURRENT_SOURCE_DIR}/durable_check.py")
set_tests_properties(cli_durable_publish PROPERTIES LABELS "cli;external-render" TIMEOUT 300 SKIP_RETURN_CODE 77)
