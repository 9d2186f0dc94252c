# Every `wangscape ...` command in the fenced ```sh blocks of README.md and docs/*.md runs, in
# order per file, on small inputs (tests/cli/doc_commands.py says how they are made small, and
# lists with a reason each the commands too long to run or needing a window or a cluster). Fails
# on a command that exits non-zero, a wangscape command in a fence not marked sh, or a stale
# skip entry. Runs POV-Ray, Blender, ffmpeg and xvfb-run: label external-render.
find_program(doc_commands_python3 python3 PATHS /usr/bin NO_DEFAULT_PATH)  # the one with python3-numpy
add_test(NAME doc_commands
  COMMAND "${doc_commands_python3}" "${CMAKE_CURRENT_LIST_DIR}/doc_commands.py"
          --bin "${WANGSCAPE_BIN}" --source "${PROJECT_SOURCE_DIR}" --scratch "${CLI_SCRATCH}/doc_commands")
set_tests_properties(doc_commands PROPERTIES LABELS "cli;docs;external-render" TIMEOUT 600)
