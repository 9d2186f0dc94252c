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
