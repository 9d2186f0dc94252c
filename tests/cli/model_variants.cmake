# A species of four variants, the round tulips' folder (tests/data/models/tulips, 576 triangles
# each), with camera-aware export (issue 38, parts 2 and 3): POV-Ray's models.inc declares the
# four tulips and their four stand-ins, named by species and variant, both are placed, and the
# build's line gives each stand-in's triangles (at most proxy_triangles, 400) and error (meters).
set(variants_dir "${CLI_SCRATCH}/model_variants")
file(MAKE_DIRECTORY "${variants_dir}")
tiny_scene("${variants_dir}/tulips.toml"
           EXPORTS "povray = true\n[camera_aware]\nenabled = true\nnear = 6.0\nfar = 30.0\n[[species]]\nname = \"tulip\"\nmodel = \"${PROJECT_SOURCE_DIR}/tests/data/models/tulips\"")
set(stand_in_figures "tulip_[0-3] proxy ([1-9]|[1-9][0-9]|[1-3][0-9][0-9]|400) of 576 triangles, error 0\\.[0-9]+ m")
add_test(NAME model_variants_stand_ins
  COMMAND ${cli_expect} 0
          "stand-ins: ${stand_in_figures}; ${stand_in_figures}; ${stand_in_figures}; ${stand_in_figures}, [0-9.]+ [kM]B\\)"
          sh -c "rm -rf \"$1\" && \"$0\" build \"$1.toml\" --out \"$1\" && grep -q 'Wangscape_Model_Count = 8;' \"$1/models.inc\" && for v in 0 1 2 3; do grep -q \"^#declare Tulip_\${v} = mesh2\" \"$1/models.inc\" && grep -q \"^#declare Tulip_\${v}_proxy = mesh2\" \"$1/models.inc\" || exit 1; done && grep -q 'object{Tulip_[0-3] ' \"$1/instances.inc\" && grep -q 'object{Tulip_[0-3]_proxy ' \"$1/instances.inc\""
          "${WANGSCAPE_BIN}" "${variants_dir}/tulips")

# Issue 38's goal: the same species of four variants with stand-ins builds the default field
# (templates/scenes/default.toml, the tulips in place of its sunflowers, camera-aware on, at
# 160 x 90): every variant and its stand-in declared, near plants whole and far ones stood in,
# and POV-Ray shows the red heads (57 red pixels measured).
find_program(variants_python3 python3 PATHS /usr/bin NO_DEFAULT_PATH)  # the one with python3-numpy
set(default_stand_in "tulip_[1-4]_[0-3] proxy ([1-9]|[1-9][0-9]|[1-3][0-9][0-9]|400) of 576 triangles, error 0\\.[0-9]+ m")
file(READ "${PROJECT_SOURCE_DIR}/templates/scenes/default.toml" default_text)
string(REPLACE "\"data/SainteHelens.dem\"" "\"${PROJECT_SOURCE_DIR}/data/SainteHelens.dem\"" default_text "${default_text}")
string(REGEX REPLACE "\nvariants = [0-9]+" "\nmesh = \"${PROJECT_SOURCE_DIR}/tests/data/models/tulips\"" default_text "${default_text}")
string(REGEX REPLACE "\nwidth = [0-9]+" "\nwidth = 160" default_text "${default_text}")
string(REGEX REPLACE "\nheight = [0-9]+" "\nheight = 90" default_text "${default_text}")
string(REGEX REPLACE "\nbake_pixels = [0-9]+" "\nbake_pixels = 1024" default_text "${default_text}")
file(WRITE "${variants_dir}/default_field.toml" "${default_text}\n[camera_aware]\nenabled = true\n")
add_test(NAME model_variants_default_field
  COMMAND ${cli_expect} 0
          "flowers: [1-9][0-9]* models, [1-9][0-9]* proxies; stand-ins: ${default_stand_in}; ${default_stand_in}; ${default_stand_in}; ${default_stand_in}, [0-9.]+ [kM]B\\)"
          sh -c "rm -rf \"$1\" && \"$0\" build \"$1.toml\" --out \"$1\" && grep -q 'Wangscape_Model_Count = 8;' \"$1/models.inc\" && for v in 0 1 2 3; do grep -q \"^#declare Tulip_[1-4]_\${v} = mesh2\" \"$1/models.inc\" && grep -q \"^#declare Tulip_[1-4]_\${v}_proxy = mesh2\" \"$1/models.inc\" || exit 1; done && grep -q 'object{Tulip_[1-4]_[0-3] ' \"$1/instances.inc\" && grep -q 'object{Tulip_[1-4]_[0-3]_proxy ' \"$1/instances.inc\" && \"$0\" --quiet render \"$1\" --engine povray && \"$2\" \"$3\" \"$1/render.png\" red:min:30"
          "${WANGSCAPE_BIN}" "${variants_dir}/default_field" "${variants_python3}" "${CMAKE_CURRENT_SOURCE_DIR}/model_colors.py")
set_tests_properties(model_variants_default_field PROPERTIES TIMEOUT 180 LABELS external-render)
