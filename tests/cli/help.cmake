# Help that says what a thing is: no subcommand's --help names a paper by its seed number or shows
# an option's type as "TEXT x 2" (tests/cli/help_words.sh walks every subcommand).
add_test(NAME help_words COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/help_words.sh" "${WANGSCAPE_BIN}")
add_test(NAME help_tiles_preview_type
  COMMAND ${cli_expect} 0 "--preview WxH FILE +Also write a WxH-pixel image FILE"
          "${WANGSCAPE_BIN}" texture tiles --help)
# Help that teaches (issue 24): every --help says what it writes and ends with two or three
# examples from the repository root; tests/cli/help_examples.sh runs each one (the few that take
# half a minute are named there) in a scratch folder laid out like the checkout.
add_test(NAME help_examples
  COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/help_examples.sh" "${WANGSCAPE_BIN}" "${PROJECT_SOURCE_DIR}"
          "${CLI_SCRATCH}/help_examples")
set_tests_properties(help_examples PROPERTIES LABELS cli TIMEOUT 300)
# Every "[section] key = value" hint in a message, help text or document names a key of
# docs/scene-file.md as the file spells it (issue 40: a hint named [export]).
add_test(NAME help_scene_key_hints COMMAND python3 "${CMAKE_CURRENT_SOURCE_DIR}/key_hints.py" "${PROJECT_SOURCE_DIR}")
set_tests_properties(help_scene_key_hints PROPERTIES LABELS cli)
