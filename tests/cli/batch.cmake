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
# The Embree reference beside POV-Ray (issue 39): 1 viewpoint x 2 suns x 2 engines.
file(WRITE "${batch_dir}/engines.toml" [=[
scene = "tiny.toml"
width = 48
height = 36
engines = ["embree", "povray"]
[[viewpoints]]
kind = "flowers"
count = 1
[sun]
angles = [[120.0, 30.0], [240.0, 50.0]]
]=])
# A path's frames in parts (issue 39 part 3): 0.7 s at 10 frames/s (8 frames) in parts of 3, in
# POV-Ray and Embree: 6 tasks, each path's frames and path.mp4 under paths/.
file(WRITE "${batch_dir}/walk.json"
  "{\"keyframes\": [{\"time\": 0, \"position\": [0, -16], \"height_above_ground\": 2.2, \"look_at\": [0, 0], \"look_at_height_above_ground\": 1.2},\n"
  "                {\"time\": 0.7, \"position\": [2, -10], \"height_above_ground\": 2.0, \"look_at\": [0, 4], \"look_at_height_above_ground\": 1.0}]}\n")
file(WRITE "${batch_dir}/paths.toml" [=[
scene = "tiny.toml"
width = 48
height = 36
engines = ["povray", "embree"]
[[viewpoints]]
kind = "flowers"
count = 1
[[paths]]
file = "walk.json"
fps = 10
frames_per_task = 3
]=])
# A cropped real DEM: one still per viewpoint kind (flowers, summit, grid, 2 path points) x 2 suns.
file(WRITE "${batch_dir}/dem_scene.toml" "name = \"boulder\"
[terrain]
dem = \"${PROJECT_SOURCE_DIR}/tests/data/dem/SRTMGL3_boulder_CO_240x144.asc\"
crop = [-600.0, -600.0, 600.0, 600.0]
[tiles]
points_per_tile = 6
area = [-24.0, -24.0, 24.0, 24.0]
[models]
variants = 2
triangle_budget = 400
")
file(WRITE "${batch_dir}/dem.toml" [=[
scene = "dem_scene.toml"
width = 40
height = 30
[[viewpoints]]
kind = "flowers"
count = 1
[[viewpoints]]
kind = "summits"
count = 1
[[viewpoints]]
kind = "grid"
grid = [1, 1]
[[viewpoints]]
kind = "path"
enu = [[-10.0, -10.0], [10.0, 10.0]]
[sun]
from = 2024-07-15T09:00:00-06:00
to = 2024-07-15T15:00:00-06:00
step_minutes = 360
]=])
foreach(scenario IN ITEMS plan example local embree paths kill missing_dem failing terrain slurm)
  add_test(NAME batch_${scenario}
    COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/batch/scenario.sh" ${scenario} "${WANGSCAPE_BIN}" "${batch_dir}")
  set_tests_properties(batch_${scenario} PROPERTIES TIMEOUT 120 SKIP_RETURN_CODE 77 RESOURCE_LOCK batch_dir)
endforeach()
