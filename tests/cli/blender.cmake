# wangscape build with [exports] blender/gltf, then `wangscape render --engine blender` with the
# real Blender (issue 6). A tiny flat field at 160x120 keeps the Blender run to a few seconds.
set(blender_dir "${CLI_SCRATCH}/blender")
file(MAKE_DIRECTORY "${blender_dir}")
file(WRITE "${blender_dir}/field.toml" [=[
name = "blender tiny"
[terrain]
flat_size = 60.0
[tiles]
set = "cohen8"
tile_size = 4.0
points_per_tile = 10
seed = 5
area = [-12.0, -12.0, 12.0, 12.0]
[models]
variants = 3
triangle_budget = 600
[camera]
position = [0.0, -16.0, 2.2]
target = [0.0, 0.0, 1.2]
fov = 60.0
[sun]
azimuth = 200.0
elevation = 40.0
[image]
width = 160
height = 120
antialias = 1
[exports]
povray = false
blender = true
gltf = true
]=])

# Build: the Blender folder (manifest, arrays, add-on zip) and scene.glb, which the Khronos
# validator accepts with 0 errors.
add_test(NAME blender_build_exports
  COMMAND sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && test -s \"$1/blender/manifest.json\" && test -s \"$1/blender/instances_variant.u16\" && test -s \"$1/blender/wangscape_import.zip\" && node \"$2/tools/validate_gltf.mjs\" \"$1/scene.glb\""
          "${WANGSCAPE_BIN}" "${blender_dir}/field" "${PROJECT_SOURCE_DIR}")
set_tests_properties(blender_build_exports PROPERTIES PASS_REGULAR_EXPRESSION "scene.glb: 0 errors")

# Render: the add-on imports the build in headless Blender; Cycles writes the PNG and the
# .blend, the log is kept; then the import is checked inside Blender against the manifest.
add_test(NAME blender_render_engine
  COMMAND sh -c "\"$0\" --quiet render \"$1\" --engine blender && test -s \"$1/render_blender.png\" && test -s \"$1/scene.blend\" && test -s \"$1/blender.log\" && blender -b --factory-startup --python-exit-code 1 --python \"$2/tests/blender/check_import.py\" -- \"$1/blender/wangscape_import.zip\" \"$1/blender/manifest.json\""
          "${WANGSCAPE_BIN}" "${blender_dir}/field" "${PROJECT_SOURCE_DIR}")
set_tests_properties(blender_render_engine PROPERTIES DEPENDS blender_build_exports
  PASS_REGULAR_EXPRESSION "wangscape-check: OK: [1-9][0-9]* instances")

# An unknown engine is named; a folder without a Blender export says how to get one.
add_test(NAME blender_render_unknown_engine
  COMMAND "${WANGSCAPE_BIN}" render "${blender_dir}" --engine mitsuba)
set_tests_properties(blender_render_unknown_engine PROPERTIES WILL_FAIL FALSE
  PASS_REGULAR_EXPRESSION "engine 'mitsuba' is not available.*povray, blender")
add_test(NAME blender_render_without_export
  COMMAND sh -c "mkdir -p \"$1\" && \"$0\" render \"$1\" --engine blender; test $? -eq 1"
          "${WANGSCAPE_BIN}" "${blender_dir}/empty")
set_tests_properties(blender_render_without_export PROPERTIES
  PASS_REGULAR_EXPRESSION "blender/manifest.json.*blender = true")
