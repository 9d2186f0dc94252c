# wangscape build / render / demo with the real POV-Ray (issue 5). Tiny images (96x72) on flat
# ground keep these fast; the demo runs the embedded Mount St. Helens scene end to end.
set(povray_dir "${CLI_SCRATCH}/povray")
file(MAKE_DIRECTORY "${povray_dir}")
# povray_scene(NAME MODELS IMAGE): the tiny scene (tests/cli/tiny_scene.toml) as NAME.toml.
function(povray_scene name models image)
  tiny_scene("${povray_dir}/${name}.toml" MODELS "${models}" IMAGE "${image}" EXPORTS "povray = true")
endfunction()

# A user mesh: a yellow octahedron on a stick, as OBJ.
file(WRITE "${povray_dir}/user_flower.obj" [=[
# user flower
v 0 0 0
v 0.05 0 0
v 0 0.05 0
v 0 0 1.5
v 0.3 0 1.5
v -0.3 0 1.5
v 0 0.3 1.5
v 0 -0.3 1.5
v 0 0 1.8
v 0 0 1.2
usemtl stem
f 1 2 4
f 1 4 3
usemtl petal
f 5 7 9
f 7 6 9
f 6 8 9
f 8 5 9
f 7 5 10
f 6 7 10
f 8 6 10
f 5 8 10
]=])

povray_scene(povray_tiny "" "")
povray_scene(povray_radiosity "" "radiosity = true")
povray_scene(povray_antialias "" "antialias = 3")
povray_scene(povray_user_mesh "mesh = \"user_flower.obj\"" "")
# The same flower in a y-up file (x, y, z) -> (x, z, -y): up_axis = "y" stands it upright again.
file(READ "${povray_dir}/user_flower.obj" flower_y_up)
string(REPLACE "v 0 0.05 0\n" "v 0 0 -0.05\n" flower_y_up "${flower_y_up}")
foreach(vertex IN ITEMS "0 0 1.5|0 1.5 0" "0.3 0 1.5|0.3 1.5 0" "-0.3 0 1.5|-0.3 1.5 0" "0 0.3 1.5|0 1.5 -0.3"
                        "0 -0.3 1.5|0 1.5 0.3" "0 0 1.8|0 1.8 0" "0 0 1.2|0 1.2 0")
  string(REPLACE "|" ";" pair "${vertex}")
  list(GET pair 0 from)
  list(GET pair 1 to)
  string(REPLACE "v ${from}\n" "v ${to}\n" flower_y_up "${flower_y_up}")
endforeach()
file(WRITE "${povray_dir}/user_flower_y_up.obj" "${flower_y_up}")
povray_scene(povray_user_mesh_y_up "mesh = \"user_flower_y_up.obj\"\nup_axis = \"y\"" "")
# Both user meshes stand upright: the flower's top (ENU 0, 0, 1.8) is POV-Ray's <0, 1.8, 0>.
foreach(variant IN ITEMS povray_user_mesh povray_user_mesh_y_up)
  add_test(NAME ${variant}_upright COMMAND grep -q "<0.00000,1.80000,0.00000>" "${povray_dir}/${variant}/models.inc")
  set_tests_properties(${variant}_upright PROPERTIES DEPENDS ${variant}_build_render)
endforeach()
# A user tile set as JSON (the one `wangscape tileset --json` prints), named by the scene file.
add_test(NAME povray_user_tileset_json
  COMMAND sh -c "rm -rf \"$1\" && \"$0\" tileset --set cohen12 --json > \"$2/mine.json\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && \"$0\" --quiet render \"$1\" && test -s \"$1/render.png\" && grep -q 'Sunflower_0' \"$1/instances.inc\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_user_tileset" "${povray_dir}")
tiny_scene("${povray_dir}/povray_user_tileset.toml" TILES "" EXPORTS "povray = true")
file(READ "${povray_dir}/povray_user_tileset.toml" tileset_text)
string(REPLACE "set = \"cohen8\"" "set = \"mine.json\"" tileset_text "${tileset_text}")
file(WRITE "${povray_dir}/povray_user_tileset.toml" "${tileset_text}")
# The instances name their model: the procedural sunflowers Sunflower_N, a user's OBJ by its file.
foreach(variant IN ITEMS povray_tiny povray_radiosity povray_antialias povray_user_mesh povray_user_mesh_y_up)
  set(model_name "Sunflower_0")
  if(variant STREQUAL "povray_user_mesh")
    set(model_name "User_flower")
  elseif(variant STREQUAL "povray_user_mesh_y_up")
    set(model_name "User_flower_y_up")
  endif()
  add_test(NAME ${variant}_build_render
    COMMAND sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && \"$0\" --quiet render \"$1\" --engine povray && test -s \"$1/render.png\" && test -s \"$1/povray.log\" && grep -q \"object{$2 \" \"$1/instances.inc\""
            "${WANGSCAPE_BIN}" "${povray_dir}/${variant}" "${model_name}")
endforeach()

# --width/--height override the scene's size.
add_test(NAME povray_render_size
  COMMAND ${cli_expect} 0 "0 +0 +0 +40 +0 +0 +0 +30"
          sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && \"$0\" --quiet render \"$1\" --width 40 --height 30 && od -An -tu1 -j16 -N8 \"$1/render.png\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_size")
povray_scene(povray_size "" "")
# One side alone keeps the scene's aspect (96 x 72: --width 48 gives 48 x 36), and --out takes
# POV-Ray's image too (issue 40: it was refused), the folder's render.png beside it.
add_test(NAME povray_render_one_side_out
  COMMAND ${cli_expect} 0 "0 +0 +0 +48 +0 +0 +0 +36"
          sh -c "rm -rf \"$1\" \"$1.png\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && \"$0\" --quiet render \"$1\" --width 48 --out \"$1.png\" && test -s \"$1/render.png\" && od -An -tu1 -j16 -N8 \"$1.png\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_one_side")
povray_scene(povray_one_side "" "")

# Unknown keys are errors naming the key and its line (line 17 is `fvo` below).
file(WRITE "${povray_dir}/unknown_key.toml" "name = \"bad\"\n[terrain]\nflat_size = 50.0\n[tiles]\ntile_size = 4.0\n[camera]\nfov = 50.0\n\n\n\n\n\n\n\n\n\nfvo = 40.0\n")
add_test(NAME povray_unknown_key
  COMMAND ${cli_expect} 1 "unknown_key.toml:17: unknown key 'camera.fvo'"
          "${WANGSCAPE_BIN}" build "${povray_dir}/unknown_key.toml" --out "${povray_dir}/unknown_key")
file(WRITE "${povray_dir}/unknown_section.toml" "[camera]\nfov = 50.0\n[sky]\ncolor = 1\n")
add_test(NAME povray_unknown_section
  COMMAND ${cli_expect} 1 "unknown_section.toml:3: unknown key 'sky'"
          "${WANGSCAPE_BIN}" build "${povray_dir}/unknown_section.toml" --out "${povray_dir}/unknown_section")
file(WRITE "${povray_dir}/wrong_type.toml" "[tiles]\ntile_size = \"big\"\n")
add_test(NAME povray_wrong_type
  COMMAND ${cli_expect} 1 "wrong_type.toml:2: 'tiles.tile_size' must be a number"
          "${WANGSCAPE_BIN}" build "${povray_dir}/wrong_type.toml" --out "${povray_dir}/wrong_type")
# A failed build leaves no output folder behind, nor its staging folder (".NAME.partial-PID"). Its
# own output name: povray_wrong_type builds the same file at the same time, and other tests stage
# their folders beside it.
add_test(NAME povray_failed_build_leaves_nothing
  COMMAND sh -c "rm -rf \"$1\"; \"$0\" build \"$2\" --out \"$1\"; test $? -eq 1 && test ! -e \"$1\" && ! ls -a \"$(dirname \"$1\")\" | grep -q '^\\.failed_build\\.partial'"
          "${WANGSCAPE_BIN}" "${povray_dir}/failed_build" "${povray_dir}/wrong_type.toml")

# The sun from a date and time: 2024-07-20 18:30 PDT at 46.19 N 122.19 W is in the west-north-
# west, about 22 degrees up (NOAA calculator: azimuth 276.8, elevation 22.3).
tiny_scene("${povray_dir}/povray_sun_time.toml" TERRAIN "origin_latitude = 46.1914\norigin_longitude = -122.1956"
           SUN "time = 2024-07-20T18:30:00-07:00" EXPORTS "povray = true")
add_test(NAME povray_sun_from_time
  COMMAND ${cli_expect} 0 "azimuth 276\\.[5-9][0-9] deg from north, elevation 22\\.[1-4]"
          sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && grep 'Sun: azimuth' \"$1/scene.pov\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_sun_time")

# POV-Ray missing or failing: a clear error, exit 1.
# (The render's own exit code is checked: 1, and no render.png; then the message.)
add_test(NAME povray_missing
  COMMAND ${cli_expect} 0 "POV-Ray \\('/nonexistent/povray'\\) is not installed"
          sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && { WANGSCAPE_POVRAY=/nonexistent/povray \"$0\" render \"$1\"; test $? -eq 1; } && test ! -e \"$1/render.png\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_missing")
povray_scene(povray_missing "" "")
add_test(NAME povray_render_failure_quotes_log
  COMMAND ${cli_expect} 0 "POV-Ray exited with status [0-9]+.*last lines:"
          sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && echo 'broken {' >> \"$1/scene.pov\" && { \"$0\" render \"$1\"; test $? -eq 1; } && test ! -e \"$1/render.png\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_broken")
povray_scene(povray_broken "" "")

find_program(system_python3 python3 PATHS /usr/bin NO_DEFAULT_PATH)  # the one with python3-numpy

# The main job: the embedded default scene, built and rendered (issue 5: under 2 minutes).
add_test(NAME povray_demo
  COMMAND sh -c "rm -rf \"$1\" && \"$0\" --quiet demo --out \"$1\" && test -s \"$1/render.png\" && test -s \"$1/scene.toml\""
          "${WANGSCAPE_BIN}" "${povray_dir}/demo")
set_tests_properties(povray_demo PROPERTIES TIMEOUT 120)

# Seed 003's meadow (issue 26): `demo --scene meadow` builds three species on Mount St. Helens and
# renders them; the still below the horizon is mostly green with yellow heads in it (0.1 % of the
# pixels; 0.02 % when the dandelions stood buried under the DEM's flat triangles).
add_test(NAME povray_demo_meadow
  COMMAND ${cli_expect} 0 "meadow rows .* yellow 0\\.[0-9]+"
          sh -c "rm -rf \"$1\" && \"$0\" --quiet demo --scene meadow --out \"$1\" && test -s \"$1/tiles.json\" && \"$2\" \"$3\" \"$1/render.png\" 0.3 0.5 0.0005"
          "${WANGSCAPE_BIN}" "${povray_dir}/demo_meadow" "${system_python3}" "${CMAKE_CURRENT_SOURCE_DIR}/meadow_colors.py")
set_tests_properties(povray_demo_meadow PROPERTIES TIMEOUT 120)
# --scene names a shipped scene or is refused naming the flag; --print-scene prints the shipped
# scene with its DEM's path made absolute (a copy saved anywhere still builds).
add_test(NAME demo_unknown_scene
  COMMAND ${cli_expect} 1 "--scene 'prairie': expected default, meadow, small or whole-dem"
          "${WANGSCAPE_BIN}" demo --scene prairie --out "${povray_dir}/prairie")
add_test(NAME demo_print_meadow
  COMMAND ${cli_expect} 0 "dem = \"/.*/data/SainteHelens.dem\"" "${WANGSCAPE_BIN}" demo --scene meadow --print-scene)

# The ground look ([ground]): the ground of the still is not one color. Flowers shrunk to 1 cm
# leave the ground in view; the luminance over the lower rows (all ground) must vary, and the
# same scene without [ground] (one flat color) is below that bar, so the check can fail.
foreach(look IN ITEMS ground plain)
  set(ground_lines "[ground]\nbake_pixels = 512\nnoise_scale = 8.0\ntexture_scale = 2.0")
  if(look STREQUAL "plain")
    set(ground_lines "")
  endif()
  tiny_scene("${povray_dir}/povray_${look}_look.toml" MODELS "scale = 0.01"
             EXPORTS "povray = true\n${ground_lines}")
endforeach()
add_test(NAME povray_ground_look_varies
  COMMAND ${cli_expect} 0 "luminance stddev ([5-9]|[1-9][0-9])\\."
          sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && test -s \"$1/ground.png\" && grep -q 'image_map { png \"ground.png\"' \"$1/scene.pov\" && \"$0\" --quiet render \"$1\" --width 160 --height 120 && \"$2\" \"$3\" \"$1/render.png\" 0.6 1.0 5"
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_ground_look" "${system_python3}" "${CMAKE_CURRENT_SOURCE_DIR}/ground_variance.py")
add_test(NAME povray_plain_ground_is_one_color
  COMMAND ${cli_expect} 0 "luminance stddev [0-4]\\."
          sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && test ! -e \"$1/ground.png\" && \"$0\" --quiet render \"$1\" --width 160 --height 120 && { \"$2\" \"$3\" \"$1/render.png\" 0.6 1.0 5; test $? -eq 1; }"
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_plain_look" "${system_python3}" "${CMAKE_CURRENT_SOURCE_DIR}/ground_variance.py")

# [ground] errors name the key and its line.
file(WRITE "${povray_dir}/ground_unknown.toml" "[terrain]\nflat_size = 50.0\n[ground]\nlook = \"both\"\ncolour = 3\n")
add_test(NAME povray_ground_unknown_key
  COMMAND ${cli_expect} 1 "ground_unknown.toml:5: unknown key 'ground.colour'"
          "${WANGSCAPE_BIN}" build "${povray_dir}/ground_unknown.toml" --out "${povray_dir}/ground_unknown")
file(WRITE "${povray_dir}/ground_range.toml" "[ground]\n\nrock_slope = 120.0\n")
add_test(NAME povray_ground_out_of_range
  COMMAND ${cli_expect} 1 "ground_range.toml:3: 'ground.rock_slope' must be between 0 and 90"
          "${WANGSCAPE_BIN}" build "${povray_dir}/ground_range.toml" --out "${povray_dir}/ground_range")
file(WRITE "${povray_dir}/ground_look.toml" "[ground]\nlook = \"plaid\"\n")
add_test(NAME povray_ground_bad_look
  COMMAND ${cli_expect} 1 "ground_look.toml:2: 'ground.look' must be \"materials\", \"texture\" or \"both\""
          "${WANGSCAPE_BIN}" build "${povray_dir}/ground_look.toml" --out "${povray_dir}/ground_look")
file(WRITE "${povray_dir}/ground_exemplar.toml" "[terrain]\nflat_size = 50.0\n[ground]\nexemplar = \"gravel\"\n")
add_test(NAME povray_ground_unknown_exemplar
  COMMAND ${cli_expect} 1 "ground_exemplar.toml:4: 'ground.exemplar' 'gravel' is no shipped exemplar"
          "${WANGSCAPE_BIN}" build "${povray_dir}/ground_exemplar.toml" --out "${povray_dir}/ground_exemplar")
