# wangscape build with [exports] blender/gltf, then `wangscape render --engine blender` with the
# real Blender (issue 6). A tiny flat field at 160x120 keeps the Blender run to a few seconds.
set(blender_dir "${CLI_SCRATCH}/blender")
file(MAKE_DIRECTORY "${blender_dir}")
# With a [ground] look: the baked texture goes into the Blender material and the .glb.
tiny_scene("${blender_dir}/field.toml" TERRAIN "" IMAGE "antialias = 1"
           EXPORTS "povray = false\nblender = true\ngltf = true\n[ground]\nbake_pixels = 256\ntexture_scale = 4.0")

# Build: the Blender folder (manifest, arrays, add-on zip) and scene.glb, which the Khronos
# validator accepts with 0 errors.
add_test(NAME blender_build_exports
  COMMAND ${cli_expect} 0 "scene.glb: 0 errors" sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && test -s \"$1/blender/manifest.json\" && test -s \"$1/blender/instances_variant.u16\" && test -s \"$1/blender/wangscape_import.zip\" && test -s \"$1/blender/ground.png\" && grep -aq baseColorTexture \"$1/scene.glb\" && node \"$2/tools/validate_gltf.mjs\" \"$1/scene.glb\""
          "${WANGSCAPE_BIN}" "${blender_dir}/field" "${PROJECT_SOURCE_DIR}")

# Render: the add-on imports the build in headless Blender; Cycles writes the PNG and the
# .blend, the log is kept; then the import is checked inside Blender against the manifest.
add_test(NAME blender_render_engine
  COMMAND ${cli_expect} 0 "wangscape-check: OK: [1-9][0-9]* instances" sh -c "\"$0\" --quiet render \"$1\" --engine blender && test -s \"$1/render_blender.png\" && test -s \"$1/scene.blend\" && test -s \"$1/blender.log\" && blender -b --factory-startup --python-exit-code 1 --python \"$2/tests/blender/check_import.py\" -- \"$1/blender/wangscape_import.zip\" \"$1/blender/manifest.json\""
          "${WANGSCAPE_BIN}" "${blender_dir}/field" "${PROJECT_SOURCE_DIR}")
set_tests_properties(blender_render_engine PROPERTIES DEPENDS blender_build_exports)

# [[species]] (issue 26): three species of the meadow on the tiny field; the import gives every
# flower its species attribute (its model's species) and every species shows in Blender; the
# scene's .glb with three species passes the Khronos validator.
tiny_scene("${blender_dir}/species.toml" TERRAIN "" IMAGE "antialias = 1"
           EXPORTS "povray = false\nblender = true\ngltf = true\n[[species]]\nname = \"grass\"\nmodel = \"grass\"\nvariants = 2\ntriangle_budget = 100\nshare = 6\n[[species]]\nname = \"dandelion\"\nmodel = \"wildflower\"\nvariants = 2\ntriangle_budget = 300\nshare = 3\n[[species]]\nname = \"sunflower\"\nmodel = \"sunflower\"\nvariants = 1\ntriangle_budget = 400\nshare = 1")
add_test(NAME blender_species
  COMMAND ${cli_expect} 0 "wangscape-check: OK: [1-9][0-9]* instances, 5 variants, 3 species" sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && node \"$2/tools/validate_gltf.mjs\" \"$1/scene.glb\" && blender -b --factory-startup --python-exit-code 1 --python \"$2/tests/blender/check_import.py\" -- \"$1/blender/wangscape_import.zip\" \"$1/blender/manifest.json\""
          "${WANGSCAPE_BIN}" "${blender_dir}/species" "${PROJECT_SOURCE_DIR}")

# An unknown engine is named; a folder without a Blender export says how to get one.
add_test(NAME blender_render_unknown_engine
  COMMAND ${cli_expect} 1 "engine 'mitsuba' is not available.*povray, blender"
          "${WANGSCAPE_BIN}" render "${blender_dir}" --engine mitsuba)
add_test(NAME blender_render_without_export
  COMMAND ${cli_expect} 1 "blender/manifest.json.*blender = true"
          sh -c "mkdir -p \"$1\" && exec \"$0\" render \"$1\" --engine blender" "${WANGSCAPE_BIN}" "${blender_dir}/empty")
