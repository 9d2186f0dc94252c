# wangscape view on a tiny flat field built with the LDI export (2 levels, 2 directions, no sky
# rays): an offline frame, --stats --json with exactly its keys, path playback with ffmpeg, the
# window under a real Xvfb driven by a script (its screenshot is the offline frame of the same
# camera, and not one color), and the refusals of bad flags and folders.
set(view_dir "${CLI_SCRATCH}/view")
file(MAKE_DIRECTORY "${view_dir}")
tiny_scene("${view_dir}/field.toml" EXPORTS "povray = false\nldi = true\n[ldi]\nlevels = 2\ndirections = 2\nsky_rays = 0")
set(view_folder "${view_dir}/field")
find_program(system_python3 python3 PATHS /usr/bin NO_DEFAULT_PATH)  # the one with python3-numpy

function(view_test name)
  add_test(NAME cli_view_${name} COMMAND ${ARGN})
  set_tests_properties(cli_view_${name} PROPERTIES LABELS "cli;view" TIMEOUT 120 FIXTURES_REQUIRED view_folder)
endfunction()

# view_sh_test(NAME REGEX SCRIPT [ARGS...]): `sh -c SCRIPT` with $0 the program, $1 the folder,
# $2 the system python, $3... ARGS; passes on exit 0 with REGEX in its output.
function(view_sh_test name regex script)
  view_test(${name} ${cli_expect} 0 "${regex}" sh -c "${script}" "${WANGSCAPE_BIN}" "${view_folder}" "${system_python3}" ${ARGN})
endfunction()
set(ground_variance "${CMAKE_CURRENT_LIST_DIR}/ground_variance.py")

add_test(NAME cli_view_build
  COMMAND ${cli_expect} 0 "" sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && test -s \"$1/tiles.ldi\" && test -s \"$1/ground_light.bin\""
          "${WANGSCAPE_BIN}" "${view_folder}")
set_tests_properties(cli_view_build PROPERTIES LABELS "cli;view" TIMEOUT 300 FIXTURES_SETUP view_folder)

# One frame of the scene's own camera, not one color below the horizon.
view_sh_test(frame "stddev" "\"$0\" --quiet view \"$1\" --size 320x240 --out \"$1.frame.png\" && \"$2\" \"$3\" \"$1.frame.png\" 0.55 1.0 8"
  "${ground_variance}")

# --stats --json: exactly the documented keys; the tiny field's 36 tiles are drawn or culled.
view_sh_test(stats_json "^ok 36 levels 3$"
  "\"$0\" --quiet view \"$1\" --camera 0,-16,2.2 --look-at 0,0,1.2 --size 320x240 --stats --json --repeat 5 | \"$2\" \"$3\""
  "${CMAKE_CURRENT_LIST_DIR}/view_stats_check.py")

# A camera looking away from the field: every tile culled, no depth pixel.
view_test(looking_away ${cli_expect} 0 "\"depth_pixels\": 0, \"tiles\": \\{\"drawn\": 0, \"culled\": 36, \"steep\": 0\\}"
  "${WANGSCAPE_BIN}" --quiet view "${view_folder}" --camera 0,-20 --look-at 0,-40,1.7 --size 32x24 --stats --json --repeat 1)

# A flythrough: 0.3 s at 10 frames/s is 4 frames, and the .mp4 through ffmpeg.
file(WRITE "${view_dir}/path.json"
  "{\"keyframes\": [{\"time\": 0, \"position\": [0, -16, 2.2], \"look_at\": [0, 0, 1.2]},\n"
  "                {\"time\": 0.3, \"position\": [2, -10, 2.0], \"look_at\": [0, 4, 1.0]}]}\n")
view_sh_test(path "path.mp4"
  "rm -rf \"$3\" && \"$0\" --quiet view \"$1\" --path \"$4\" --frames \"$3\" --fps 10 --size 48x32 && ls \"$3\" && test -s \"$3/frame-00003.png\" && test ! -e \"$3/frame-00004.png\" && test -s \"$3/path.mp4\""
  "${view_dir}/path_frames" "${view_dir}/path.json")

# The path drawn from the sample cache: --stats --json is one object with exactly its keys,
# without a frames folder; --compare-every 2 compares frames 0 and 2 (one JSON line each).
view_sh_test(path_stats_json "^ok 4 frames$"
  "\"$0\" --quiet view \"$1\" --path \"$4\" --fps 10 --size 48x32 --stats --json | \"$2\" \"$3\" stats"
  "${CMAKE_CURRENT_LIST_DIR}/view_path_check.py" "${view_dir}/path.json")
view_sh_test(path_compare_every "^ok 0 2$"
  "\"$0\" --quiet view \"$1\" --path \"$4\" --fps 10 --size 48x32 --compare-every 2 --truth-spp 4 | \"$2\" \"$3\" compare"
  "${CMAKE_CURRENT_LIST_DIR}/view_path_check.py" "${view_dir}/path.json")

# A walk given by heights above the ground: 4 frames, and the one line saying what was written
# (cli/progress.h's, as every command's: the folder, then what it holds).
file(WRITE "${view_dir}/walk.json"
  "{\"keyframes\": [{\"time\": 0, \"position\": [0, -16], \"height_above_ground\": 1.7, \"look_at\": [0, 0], \"look_at_height_above_ground\": 1.0},\n"
  "                {\"time\": 0.3, \"position\": [2, -10], \"height_above_ground\": 1.7, \"look_at\": [0, 4], \"look_at_height_above_ground\": 1.0}]}\n")
view_sh_test(path_above_ground "wrote .*walk_frames \\(4 frames of 48x32[ ;]"
  "rm -rf \"$3\" && \"$0\" view \"$1\" --path \"$4\" --frames \"$3\" --fps 10 --size 48x32 && test -s \"$3/frame-00003.png\""
  "${view_dir}/walk_frames" "${view_dir}/walk.json")
# A path refused before anything is written (a height of 1e300 m), and one that leaves the
# ground half-way (its first and last points are over it): exit 1, no frames folder left.
file(WRITE "${view_dir}/path_high.json"
  "{\"keyframes\": [{\"time\": 0, \"position\": [0, -16, 1e300], \"look_at\": [0, 0, 1]}, {\"time\": 1, \"position\": [0, -10, 2], \"look_at\": [0, 0, 1]}]}")
view_sh_test(path_refused "path_high.json:keyframes\\[0\\].position\\[2\\]: is 1e\\+300. expected meters"
  "rm -rf \"$3\" && \"$0\" --quiet view \"$1\" --path \"$4\" --frames \"$3\" --size 48x32 && exit 5 || test $? = 1 && test ! -e \"$3\""
  "${view_dir}/refused_frames" "${view_dir}/path_high.json")
file(WRITE "${view_dir}/path_off.json"
  "{\"keyframes\": [{\"time\": 0, \"position\": [0, -16], \"height_above_ground\": 2, \"look_at\": [0, 0, 1]},\n"
  " {\"time\": 0.5, \"position\": [5000, -10], \"height_above_ground\": 2, \"look_at\": [0, 0, 1]},\n"
  " {\"time\": 1, \"position\": [0, -10], \"height_above_ground\": 2, \"look_at\": [0, 0, 1]}]}")
view_sh_test(path_off_ground "path_off.json: at 0.[0-9]+ s the eye .* is not over the ground"
  "rm -rf \"$3\" && \"$0\" --quiet view \"$1\" --path \"$4\" --frames \"$3\" --fps 10 --size 48x32 && exit 5 || test $? = 1 && test ! -e \"$3\""
  "${view_dir}/off_frames" "${view_dir}/path_off.json")

# --compare writes the reference it compared against and the frame beside it (twice as wide
# plus a 4-pixel gap), and says so in one line: the files, then what each is.
view_sh_test(compare_writes "^ok 100x32$"
  "rm -f \"$3\"* && \"$0\" view \"$1\" --size 48x32 --compare --truth-spp 2 --reference \"$3ref.png\" --side-by-side \"$3sbs.png\" >/dev/null 2>\"$3log\" && test -s \"$3ref.png\" && grep -q 'wrote .*ref.png, .*sbs.png (the reference and the frame beside the reference, 48x32, ' \"$3log\" && echo ok $(oiiotool \"$3sbs.png\" --echo '{TOP.width}x{TOP.height}')"
  "${view_dir}/compare_")

# The window under a real X server: scripted keys go through SDL's event queue; the first
# screenshot (before any move) is the offline frame of the same camera, the second after a walk
# and a turn differs from it and is not one color; Escape quits with 0. A second run's screenshot
# takes the next free number (view-0003.png), the first run's kept.
view_sh_test(window "stddev"
  "rm -rf \"$1.win\" && mkdir -p \"$1.win\" && cd \"$1.win\" && xvfb-run -a -s '-screen 0 640x480x24' \"$0\" --quiet view \"$1\" --size 320x240 --script 'screenshot,W*20,mouse:60:0,D*5,screenshot,Escape' && \"$0\" --quiet view \"$1\" --size 320x240 --out offline.png && idiff -a view-0001.png offline.png && ! idiff -a view-0002.png offline.png >/dev/null && xvfb-run -a -s '-screen 0 640x480x24' \"$0\" --quiet view \"$1\" --size 320x240 --script 'W*5,screenshot,Escape' && test -f view-0003.png && idiff -a view-0001.png offline.png && \"$2\" \"$3\" view-0002.png 0.5 1.0 6"
  "${ground_variance}")
# A walk recorded in the window (K drops a keyframe) is written as a path file on exit, with the
# eye by its height above the ground, and replays offline; the window resized (by the X server,
# as a user's drag) draws its frames at the new size.
view_sh_test(window_record "^replayed 5$"
  "rm -rf \"$1.rec\" && mkdir -p \"$1.rec\" && cd \"$1.rec\" && xvfb-run -a -s '-screen 0 640x480x24' \"$0\" --quiet view \"$1\" --size 160x120 --record walk.json --script 'W*10,K,W*30,mouse:40:0,K,size:200:100,wait*3,screenshot,Escape' && grep -q '\"height_above_ground\": 1.7' walk.json && test \"$(oiiotool view-0001.png --echo '{TOP.width}x{TOP.height}')\" = 200x100 && \"$0\" --quiet view \"$1\" --path walk.json --frames fr --fps 4 --size 32x24 && echo replayed $(ls fr | grep -c png)")
set_property(TEST cli_view_window_record APPEND PROPERTY ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
# No display: refused at once (SDL would wait), naming the ways out.
view_test(window_no_display ${cli_expect} 1 "no display to open a window on .*xvfb-run"
  env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "${WANGSCAPE_BIN}" --quiet view "${view_folder}")
# Under the asan preset: SDL's X11 and GL drivers are dlopen'ed and unloaded, so what they keep
# until exit shows as leaks in an unknown module that no suppression can name; the other ASan
# checks stay on. (No effect on a build without ASan.)
set_property(TEST cli_view_window APPEND PROPERTY ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
view_test(window_bad_script ${cli_expect} 1 "--script: 'W\\*x' has no frame count"
  "${WANGSCAPE_BIN}" --quiet view "${view_folder}" --script "W*x")

# --engine embree: the whole frame ray cast (the anchor), not one color below the horizon; an
# unknown engine is a usage error.
view_sh_test(engine_embree "stddev" "\"$0\" --quiet view \"$1\" --engine embree --size 160x120 --out \"$1.embree.png\" && \"$2\" \"$3\" \"$1.embree.png\" 0.55 1.0 8"
  "${ground_variance}")
view_test(bad_spp ${cli_expect} 1 "--spp 0: expected 1 .. 1024 samples per pixel" "${WANGSCAPE_BIN}" view "${view_folder}" --spp 0 --out "${view_dir}/x.png")
view_test(bad_engine ${cli_expect} 2 "--engine" "${WANGSCAPE_BIN}" view "${view_folder}" --engine optix --out "${view_dir}/x.png")

# Refusals: bad sizes and angles name the flag; a folder without a pack names tiles.ldi.
view_test(bad_size ${cli_expect} 2 "--size.*0x10" "${WANGSCAPE_BIN}" view "${view_folder}" --size 0x10 --out "${view_dir}/x.png")
view_test(bad_size_text ${cli_expect} 2 "--size.*'big'" "${WANGSCAPE_BIN}" view "${view_folder}" --size big --out "${view_dir}/x.png")
view_test(bad_fov ${cli_expect} 1 "--fov 200" "${WANGSCAPE_BIN}" view "${view_folder}" --fov 200 --out "${view_dir}/x.png")
view_test(bad_detail ${cli_expect} 1 "--detail 0: expected 0.1 .. 10" "${WANGSCAPE_BIN}" view "${view_folder}" --detail 0 --out "${view_dir}/x.png")
view_test(bad_camera ${cli_expect} 2 "--camera.*'1,b'" "${WANGSCAPE_BIN}" view "${view_folder}" --camera 1,b --out "${view_dir}/x.png")
view_test(no_such_folder ${cli_expect} 1 "no_such_folder: no such scene folder" "${WANGSCAPE_BIN}" view "${view_dir}/no_such_folder" --out "${view_dir}/x.png")
# view_damaged(NAME REGEX DAMAGE): a folder NAME made by the shell commands DAMAGE ($1 the new
# folder, empty; $2 the built one) is refused by view with REGEX and exit 1, and no frame written.
function(view_damaged name regex damage)
  view_test(${name} ${cli_expect} 1 "${regex}"
    sh -c "rm -rf \"$1\" && mkdir -p \"$1\" && ${damage} && \"$0\" view \"$1\" --out \"$1/x.png\" || test ! -e \"$1/x.png\" && exit 1"
    "${WANGSCAPE_BIN}" "${view_dir}/${name}" "${view_folder}")
endfunction()
view_damaged(nopack "nopack/tiles\\.ldi: missing: build the folder from a scene with \\[exports\\] ldi"
  "cp \"$2/scene.toml\" \"$1/\"")
view_damaged(broken "broken/tiles\\.ldi: truncated"
  "cp \"$2/scene.toml\" \"$1/\" && head -c 100 \"$2/tiles.ldi\" > \"$1/tiles.ldi\"")
# A folder from an older build (no scene.cache), one whose scene.toml was edited after the build
# and one with a cut scene.cache are refused with what to do, not re-derived.
view_damaged(old "old/scene\\.cache: missing: the folder was written by an older wangscape. build the folder again"
  "cp -r \"$2\"/. \"$1\" && rm \"$1/scene.cache\"")
view_damaged(edited "edited/scene\\.toml: was changed after the build. build the folder again"
  "cp -r \"$2\"/. \"$1\" && echo '# edited' >> \"$1/scene.toml\"")
view_damaged(cut "cut/scene\\.cache: truncated: expected the placed tiles"
  "cp -r \"$2\"/. \"$1\" && head -c 60 \"$2/scene.cache\" > \"$1/scene.cache\"")
# The ground light the build baked: cut, or of another version, refused naming it.
view_damaged(ground_light_cut "ground_light_cut/ground_light\\.bin: truncated: 100 bytes, expected [0-9]+"
  "cp -r \"$2\"/. \"$1\" && head -c 100 \"$2/ground_light.bin\" > \"$1/ground_light.bin\"")
view_damaged(ground_light_version "ground_light_version/ground_light\\.bin: version 2: expected 1"
  "cp -r \"$2\"/. \"$1\" && printf '\\002' | dd of=\"$1/ground_light.bin\" bs=1 seek=8 conv=notrunc 2>/dev/null")
# A folder built before the ground light was kept (the file removed) draws the same frame from
# above, the view baking the light itself (20 m up: the LDIs and the terrain they shade, not the
# ray-traced near field).
view_sh_test(ground_light_baked "^same$"
  "rm -rf \"$3\" && cp -r \"$1\" \"$3\" && rm \"$3/ground_light.bin\" && \"$0\" --quiet view \"$1\" --camera 0.3,-1,20 --look-at 0.3,-0.5,0 --size 160x90 --out \"$3.kept.png\" && \"$0\" --quiet view \"$3\" --camera 0.3,-1,20 --look-at 0.3,-0.5,0 --size 160x90 --out \"$3.baked.png\" && cmp \"$3.kept.png\" \"$3.baked.png\" && echo same"
  "${view_dir}/no_ground_light")

# --compare against the Embree reference of the same camera: PSNR above a floor measured on this
# field (19.30 dB and SSIM 0.659 at 320 x 240, 4 samples per pixel: 2 levels, so the far field's
# one-layer LDIs start 7.5 m away), few holes, the difference image written.
view_sh_test(compare "^ok"
  "rm -f \"$1.diff.png\" && \"$0\" --quiet view \"$1\" --size 320x240 --compare --json --truth-spp 4 --diff \"$1.diff.png\" | \"$2\" \"$3\" 18.5 0.6 0.03 && test -s \"$1.diff.png\""
  "${CMAKE_CURRENT_LIST_DIR}/view_compare_check.py")
view_test(diff_needs_compare ${cli_expect} 1 "--diff: needs --compare" "${WANGSCAPE_BIN}" view "${view_folder}" --diff "${view_dir}/d.png" --out "${view_dir}/x.png")

# A build killed while it samples its LDI pack leaves the folder as the previous build made it.
tiny_scene("${view_dir}/kill.toml" EXPORTS "povray = true\nldi = true\n[ldi]\nlevels = 3\ndirections = 4\nsky_rays = 8")
foreach(signal KILL TERM)
  add_test(NAME cli_view_build_killed_in_ldi_stage_${signal}
    COMMAND sh "${CMAKE_CURRENT_LIST_DIR}/kill_during_ldi.sh" "${WANGSCAPE_BIN}" "${view_dir}/kill.toml" ${signal})
  set_tests_properties(cli_view_build_killed_in_ldi_stage_${signal} PROPERTIES LABELS "cli;view" TIMEOUT 300)
endforeach()
