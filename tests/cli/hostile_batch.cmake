# Hostile batch files, plans and output folders (issue 25): tests/cli/hostile_batch.sh, one test a
# case; none renders.
set(hostile_batch_dir "${CLI_SCRATCH}/hostile_batch")
file(MAKE_DIRECTORY "${hostile_batch_dir}")
tiny_scene("${hostile_batch_dir}/tiny.toml" EXPORTS "povray = true")
foreach(case IN ITEMS deep_key not_a_file million_tasks sun_step numbers out out_povray plan_ids utf8 utf8_run lock)
  add_test(NAME hostile_batch_${case}
    COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/hostile_batch.sh" ${case} "${WANGSCAPE_BIN}" "${hostile_batch_dir}"
            "${PROJECT_SOURCE_DIR}")
  set_tests_properties(hostile_batch_${case} PROPERTIES LABELS "cli;hostile" TIMEOUT 120 RESOURCE_LOCK hostile_batch_dir)
endforeach()
# Renders a still with POV-Ray (the asan preset leaves it out with the other renders).
set_property(TEST hostile_batch_utf8_run APPEND PROPERTY LABELS external-render)
