# wangscape build / render / demo with the real POV-Ray (issue 5). Tiny images (96x72) on flat
# ground keep these fast; the demo runs the embedded Mount St. Helens scene end to end.
set(povray_dir "${CLI_SCRATCH}/povray")
file(MAKE_DIRECTORY "${povray_dir}")
set(povray_expect sh "${CMAKE_CURRENT_SOURCE_DIR}/povray_expect.sh")

# A small flat field seen from its edge; @EXTRA@ lines are appended per test.
set(povray_tiny_scene [=[
name = "tiny"
[terrain]
flat_size = 120.0
[tiles]
set = "cohen8"
tile_size = 4.0
points_per_tile = 10
seed = 5
area = [-12.0, -12.0, 12.0, 12.0]
[models]
variants = 3
triangle_budget = 600
@MODELS@
[camera]
position = [0.0, -16.0, 2.2]
target = [0.0, 0.0, 1.2]
fov = 60.0
[sun]
azimuth = 200.0
elevation = 40.0
[image]
width = 96
height = 72
@IMAGE@
]=])

function(povray_scene name models image)
  string(REPLACE "@MODELS@" "${models}" text "${povray_tiny_scene}")
  string(REPLACE "@IMAGE@" "${image}" text "${text}")
  file(WRITE "${povray_dir}/${name}.toml" "${text}")
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
foreach(variant IN ITEMS povray_tiny povray_radiosity povray_antialias povray_user_mesh)
  add_test(NAME ${variant}_build_render
    COMMAND sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && \"$0\" --quiet render \"$1\" --engine povray && test -s \"$1/render.png\" && test -s \"$1/povray.log\" && grep -q 'Sunflower_0' \"$1/instances.inc\""
            "${WANGSCAPE_BIN}" "${povray_dir}/${variant}")
endforeach()

# --width/--height override the scene's size.
add_test(NAME povray_render_size
  COMMAND sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && \"$0\" --quiet render \"$1\" --width 40 --height 30 && od -An -tu1 -j16 -N8 \"$1/render.png\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_size")
set_tests_properties(povray_render_size PROPERTIES PASS_REGULAR_EXPRESSION "0 +0 +0 +40 +0 +0 +0 +30")
povray_scene(povray_size "" "")

# Unknown keys are errors naming the key and its line (line 17 is `fvo` below).
file(WRITE "${povray_dir}/unknown_key.toml" "name = \"bad\"\n[terrain]\nflat_size = 50.0\n[tiles]\ntile_size = 4.0\n[camera]\nfov = 50.0\n\n\n\n\n\n\n\n\n\nfvo = 40.0\n")
add_test(NAME povray_unknown_key
  COMMAND ${povray_expect} 1 "unknown_key.toml:17: unknown key 'camera.fvo'"
          "${WANGSCAPE_BIN}" build "${povray_dir}/unknown_key.toml" --out "${povray_dir}/unknown_key")
file(WRITE "${povray_dir}/unknown_section.toml" "[camera]\nfov = 50.0\n[sky]\ncolor = 1\n")
add_test(NAME povray_unknown_section
  COMMAND ${povray_expect} 1 "unknown_section.toml:3: unknown key 'sky'"
          "${WANGSCAPE_BIN}" build "${povray_dir}/unknown_section.toml" --out "${povray_dir}/unknown_section")
file(WRITE "${povray_dir}/wrong_type.toml" "[tiles]\ntile_size = \"big\"\n")
add_test(NAME povray_wrong_type
  COMMAND ${povray_expect} 1 "wrong_type.toml:2: 'tiles.tile_size' must be a number"
          "${WANGSCAPE_BIN}" build "${povray_dir}/wrong_type.toml" --out "${povray_dir}/wrong_type")
# A failed build leaves no output folder behind.
add_test(NAME povray_failed_build_leaves_nothing
  COMMAND sh -c "rm -rf \"$1\"; \"$0\" build \"$1.toml\" --out \"$1\"; test $? -eq 1 && test ! -e \"$1\" && ! ls -a \"$(dirname \"$1\")\" | grep -q partial"
          "${WANGSCAPE_BIN}" "${povray_dir}/wrong_type")

# The sun from a date and time: 2024-07-20 18:30 PDT at 46.19 N 122.19 W is in the west-north-
# west, about 22 degrees up (NOAA calculator: azimuth 276.8, elevation 22.3).
povray_scene(povray_sun_time "" "")
file(APPEND "${povray_dir}/povray_sun_time.toml" "")
file(READ "${povray_dir}/povray_sun_time.toml" sun_text)
string(REPLACE "azimuth = 200.0\nelevation = 40.0" "time = 2024-07-20T18:30:00-07:00" sun_text "${sun_text}")
string(REPLACE "flat_size = 120.0" "flat_size = 120.0\norigin_latitude = 46.1914\norigin_longitude = -122.1956" sun_text "${sun_text}")
file(WRITE "${povray_dir}/povray_sun_time.toml" "${sun_text}")
add_test(NAME povray_sun_from_time
  COMMAND sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && grep 'Sun: azimuth' \"$1/scene.pov\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_sun_time")
set_tests_properties(povray_sun_from_time PROPERTIES PASS_REGULAR_EXPRESSION "azimuth 276\\.[5-9][0-9] deg from north, elevation 22\\.[1-4]")

# POV-Ray missing or failing: a clear error, exit 1.
add_test(NAME povray_missing
  COMMAND sh -c "\"$0\" --quiet build \"$1.toml\" --out \"$1\" && WANGSCAPE_POVRAY=/nonexistent/povray \"$0\" render \"$1\"; test $? -eq 1"
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_missing")
povray_scene(povray_missing "" "")
set_tests_properties(povray_missing PROPERTIES PASS_REGULAR_EXPRESSION "POV-Ray \\('/nonexistent/povray'\\) is not installed")
add_test(NAME povray_render_failure_quotes_log
  COMMAND sh -c "\"$0\" --quiet build \"$1.toml\" --out \"$1\" && echo 'broken {' >> \"$1/scene.pov\" && \"$0\" render \"$1\"; test $? -eq 1 && test ! -e \"$1/render.png\""
          "${WANGSCAPE_BIN}" "${povray_dir}/povray_broken")
povray_scene(povray_broken "" "")
set_tests_properties(povray_render_failure_quotes_log PROPERTIES PASS_REGULAR_EXPRESSION "POV-Ray exited with status [0-9]+.*last lines:")

# The main job: the embedded default scene, built and rendered (issue 5: under 2 minutes).
add_test(NAME povray_demo
  COMMAND sh -c "rm -rf \"$1\" && \"$0\" --quiet demo --out \"$1\" && test -s \"$1/render.png\" && test -s \"$1/scene.toml\""
          "${WANGSCAPE_BIN}" "${povray_dir}/demo")
set_tests_properties(povray_demo PROPERTIES TIMEOUT 120)
