# wangscape noise tiles / texture tiles (issue 13): tiles as PNG + JSON, previews, bad input.
set(tiles_dir "${CLI_SCRATCH}/tiles")
file(MAKE_DIRECTORY "${tiles_dir}")
add_test(NAME tiles_noise
  COMMAND ${cli_expect} 0 "corner-3: 81 noise tiles, lattice 32, 3 octaves"
          sh -c "rm -rf \"$1\" && \"$0\" noise tiles --set corner-3 --lattice 32 --octaves 3 --out \"$1\" --preview 256x128 \"$1.png\" && test -s \"$1/noise_tiles.json\" && test -s \"$1/noise_tile_80.png\" && test -s \"$1.png\""
          "${WANGSCAPE_BIN}" "${tiles_dir}/noise")
add_test(NAME tiles_texture_two_exemplars
  COMMAND ${cli_expect} 0 "corner-2: 16 texture tiles of 64 px, quilting error [0-9]+"
          sh -c "rm -rf \"$1\" && \"$0\" texture tiles --exemplar meadow --exemplar2 \"$2/templates/exemplars/pumice.png\" --set corner-2 --size 64 --out \"$1\" --preview 256x128 \"$1.png\" && test -s \"$1/texture_tiles.json\" && test -s \"$1/texture_tile_15.png\" && test -s \"$1.png\""
          "${WANGSCAPE_BIN}" "${tiles_dir}/texture" "${PROJECT_SOURCE_DIR}")
# --pattern (issue 40): marble's preview differs from turbulence's (the default) over tile files of
# fbm; turbulence reaches the tile files; an unknown pattern is refused naming the flag.
add_test(NAME tiles_noise_pattern
  COMMAND ${cli_expect} 0 "^patterns ok"
          sh -c "rm -rf \"$1\"* && \"$0\" -q noise tiles --out \"$1t\" --preview 128x64 \"$1t.png\" >/dev/null && \"$0\" -q noise tiles --pattern marble --out \"$1m\" --preview 128x64 \"$1m.png\" >/dev/null && ! idiff -a \"$1t.png\" \"$1m.png\" >/dev/null && grep -q '\"pattern\": *\"fbm\"' \"$1m/noise_tiles.json\" && \"$0\" -q noise tiles --pattern turbulence --out \"$1u\" >/dev/null && grep -q '\"pattern\": *\"turbulence\"' \"$1u/noise_tiles.json\" && echo patterns ok"
          "${WANGSCAPE_BIN}" "${tiles_dir}/pattern_")
# Marble and wood read tiles beyond any window, so their preview is drawn over the hashed tiling
# of a complete set; an incomplete one (cohen8) is refused naming the flag, no preview left.
# (Exit 3: refused, but a preview or tiles folder was left.)
add_test(NAME tiles_noise_marble_needs_complete_set
  COMMAND ${cli_expect} 1 "--pattern marble: tile set 'cohen8': hash tiling needs a complete set"
          sh -c "rm -rf \"$1\" \"$1.png\" && \"$0\" noise tiles --set cohen8 --pattern marble --out \"$1\" --preview 64x64 \"$1.png\" || ( test ! -e \"$1.png\" && test ! -e \"$1\" && exit 1 || exit 3 )"
          "${WANGSCAPE_BIN}" "${tiles_dir}/bad_marble")
add_test(NAME tiles_noise_bad_pattern
  COMMAND ${cli_expect} 2 "--pattern: plaid not in"
          "${WANGSCAPE_BIN}" noise tiles --pattern plaid --out "${tiles_dir}/bad")
add_test(NAME tiles_noise_bad_lattice
  COMMAND ${cli_expect} 1 "lattice 12; expected a power of two"
          "${WANGSCAPE_BIN}" noise tiles --lattice 12 --out "${tiles_dir}/bad")
add_test(NAME tiles_bad_preview_size
  COMMAND ${cli_expect} 1 "--preview '12y4' must be WIDTHxHEIGHT"
          "${WANGSCAPE_BIN}" noise tiles --out "${tiles_dir}/bad" --preview 12y4 "${tiles_dir}/bad.png")
add_test(NAME tiles_noise_octaves_out_of_range
  COMMAND ${cli_expect} 2 "--octaves: Value 99 not in range"
          "${WANGSCAPE_BIN}" noise tiles --octaves 99 --out "${tiles_dir}/bad")
add_test(NAME tiles_texture_missing_exemplar
  COMMAND ${cli_expect} 1 "cannot read image '/nonexistent/rock.png'"
          "${WANGSCAPE_BIN}" texture tiles --exemplar /nonexistent/rock.png --out "${tiles_dir}/bad")
add_test(NAME tiles_texture_unknown_exemplar
  COMMAND ${cli_expect} 1 "'gravel' is no shipped exemplar"
          "${WANGSCAPE_BIN}" texture tiles --exemplar gravel --out "${tiles_dir}/bad")
add_test(NAME tiles_texture_needs_exemplar
  COMMAND ${cli_expect} 2 "--exemplar is required"
          "${WANGSCAPE_BIN}" texture tiles --out "${tiles_dir}/bad")
