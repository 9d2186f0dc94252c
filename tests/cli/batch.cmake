# wangscape batch (issue 12): plan, example, local runs that are repeated and killed, a missing
# DEM, a failing task, and a real single-node Slurm cluster started by the test. 4 stills of
# 48x36 over the tiny flat scene keep these fast (tests/cli/batch/scenario.sh).
set(batch_dir "${CLI_SCRATCH}/batch")
file(MAKE_DIRECTORY "${batch_dir}")
tiny_scene("${batch_dir}/tiny.toml" EXPORTS "povray = true")
file(WRITE "${batch_dir}/four.toml" [=[
scene = "tiny.toml"
width = 48
height = 36
[[viewpoints]]
kind = "flowers"
count = 2
[sun]
angles = [[120.0, 30.0], [240.0, 50.0]]
]=])
foreach(scenario IN ITEMS plan example local kill missing_dem failing slurm)
  add_test(NAME batch_${scenario}
    COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/batch/scenario.sh" ${scenario} "${WANGSCAPE_BIN}" "${batch_dir}")
  set_tests_properties(batch_${scenario} PROPERTIES TIMEOUT 120 SKIP_RETURN_CODE 77 RESOURCE_LOCK batch_dir)
endforeach()
