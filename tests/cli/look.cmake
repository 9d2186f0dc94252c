# One look (issue 39): the small scene rendered by POV-Ray, Cycles and the Embree reference at
# 160 x 90 shows the same mean colour, band by band (sky, far field, middle, near ground), within
# CIEDE2000 6 for every pair of engines. Cycles takes the scene's 16 samples (antialias = 1): a
# band's mean over thousands of pixels does not need a clean picture.
find_program(system_python3 python3 PATHS /usr/bin NO_DEFAULT_PATH)  # the one with python3-numpy
add_test(NAME render_one_look_small
  COMMAND ${cli_expect} 0 "worst CIEDE2000 [0-9.]+ \\(limit 6\\.0\\)"
          sh -c "rm -rf \"$1\" && \"$2\" \"$3/bench/band_colors.py\" --limit 6 table --wangscape \"$0\" --out \"$1\" --width 160 --height 90 \"$3/templates/scenes/small.toml\""
          "${WANGSCAPE_BIN}" "${CLI_SCRATCH}/one_look" "${system_python3}" "${PROJECT_SOURCE_DIR}")
set_tests_properties(render_one_look_small PROPERTIES TIMEOUT 300 LABELS external-render)

# The same table for a user's own plants (templates/scenes/card-plants.toml: crossed alpha cards in
# GLB files, dense): Cycles must follow rays through as many of the cards' holes as the Embree
# reference and POV-Ray do. At Cycles' default of 8 transparent bounces its middle distance was
# dark and POV-Ray-Cycles stood at 6.5 in the middle band (4.8 since, at this size).
add_test(NAME render_one_look_card_plants
  COMMAND ${cli_expect} 0 "worst CIEDE2000 [0-9.]+ \\(limit 6\\.0\\)"
          sh -c "rm -rf \"$1\" && \"$2\" \"$3/bench/band_colors.py\" --limit 6 table --wangscape \"$0\" --out \"$1\" --width 160 --height 90 \"$3/templates/scenes/card-plants.toml\""
          "${WANGSCAPE_BIN}" "${CLI_SCRATCH}/one_look_card_plants" "${system_python3}" "${PROJECT_SOURCE_DIR}")
set_tests_properties(render_one_look_card_plants PROPERTIES TIMEOUT 300 LABELS external-render)
