# Help that says what a thing is: no subcommand's --help names a paper by its seed number or shows
# an option's type as "TEXT x 2" (tests/cli/help_words.sh walks every subcommand).
add_test(NAME help_words COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/help_words.sh" "${WANGSCAPE_BIN}")
add_test(NAME help_tiles_preview_type
  COMMAND ${cli_expect} 0 "--preview WxH FILE +Also write a WxH-pixel image FILE"
          "${WANGSCAPE_BIN}" texture tiles --help)
