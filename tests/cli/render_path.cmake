# wangscape render DIR --path FILE --frames FOLDER (issue 39 part 2) and --camera/--look-at on the
# tiny field, built once with the POV-Ray, Blender and LDI exports: every engine renders 64 x 36
# frames of a 0.3 s path at 10 frames/s (4 frames; Blender 2 at 5 frames/s) and path.mp4 through
# ffmpeg; frame k of Embree and of the view frame the same view (PSNR); frames already there and
# complete are not rendered again; bad input is refused with no frames folder left.
set(rp_dir "${CLI_SCRATCH}/render_path")
file(MAKE_DIRECTORY "${rp_dir}")
tiny_scene("${rp_dir}/field.toml"
           EXPORTS "povray = true\nblender = true\nldi = true\n[ldi]\nlevels = 2\ndirections = 2\nsky_rays = 0")
set(rp_folder "${rp_dir}/field")
file(WRITE "${rp_dir}/walk.json"
  "{\"keyframes\": [{\"time\": 0, \"position\": [0, -16], \"height_above_ground\": 2.2, \"look_at\": [0, 0], \"look_at_height_above_ground\": 1.2},\n"
  "                {\"time\": 0.3, \"position\": [2, -10], \"height_above_ground\": 2.0, \"look_at\": [0, 4], \"look_at_height_above_ground\": 1.0}]}\n")

add_test(NAME render_path_build
  COMMAND ${cli_expect} 0 "" sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && test -s \"$1/tiles.ldi\" && test -s \"$1/scene.pov\""
          "${WANGSCAPE_BIN}" "${rp_folder}")
set_tests_properties(render_path_build PROPERTIES LABELS "cli;render_path" TIMEOUT 300 FIXTURES_SETUP render_path_folder)

# render_path_test(NAME REGEX SCRIPT [ARGS...]): `sh -c SCRIPT` with $0 the program, $1 the folder,
# $2 the path file, $3... ARGS; passes on exit 0 with REGEX in its output.
function(render_path_test name regex script)
  add_test(NAME render_path_${name}
    COMMAND ${cli_expect} 0 "${regex}" sh -c "${script}" "${WANGSCAPE_BIN}" "${rp_folder}" "${rp_dir}/walk.json" ${ARGN})
  set_tests_properties(render_path_${name} PROPERTIES LABELS "cli;render_path" TIMEOUT 120
                       FIXTURES_REQUIRED render_path_folder)
endfunction()
set(psnr_at_least "${CMAKE_CURRENT_LIST_DIR}/psnr_at_least.sh")

# Embree, frame by frame: 4 frames (frame-00000 .. 00003), path.mp4, the one line of what it wrote.
render_path_test(embree "wrote .*embree_frames \\(4 frames of 64x36 at 10 frames/s with embree and path.mp4"
  "rm -rf \"$3\" && \"$0\" render \"$1\" --engine embree --path \"$2\" --frames \"$3\" --fps 10 --width 64 --height 36 --spp 4 && test -s \"$3/frame-00003.png\" && test ! -e \"$3/frame-00004.png\" && test -s \"$3/path.mp4\" && ls -a \"$3\""
  "${rp_dir}/embree_frames")
set_tests_properties(render_path_embree PROPERTIES FIXTURES_SETUP render_path_embree_frames)

# Frame k of the view and of Embree frame the same view: the view's frames of the same path, file
# for file, within a loose PSNR (the view is LDIs at one sample, Embree exact at 4; measured 18.2
# and 17.6 dB for frames 0 and 3, against 15.3 and 15.7 dB between frames 0 and 3).
render_path_test(view_matches_embree "PSNR [0-9.]+ dB"
  "rm -rf \"$3\" && \"$0\" --quiet view \"$1\" --path \"$2\" --frames \"$3\" --fps 10 --size 64x36 --no-cache && sh \"$5\" \"$3/frame-00000.png\" \"$4/frame-00000.png\" 16.5 && sh \"$5\" \"$3/frame-00003.png\" \"$4/frame-00003.png\" 16.5"
  "${rp_dir}/view_frames" "${rp_dir}/embree_frames" "${psnr_at_least}")
set_tests_properties(render_path_view_matches_embree PROPERTIES FIXTURES_REQUIRED "render_path_folder;render_path_embree_frames")

# Resume: of 4 frames, frame 0 cut short and frames 1 and 3 missing are rendered; frame 2, a
# complete PNG of the size (here frame 0's picture), is kept as it was: not rendered again.
render_path_test(resume "wrote .*resume_frames \\(4 frames of 64x36 at 10 frames/s with embree, 1 there already"
  "rm -rf \"$3\" && mkdir -p \"$3\" && cp \"$4/frame-00000.png\" \"$3/frame-00002.png\" && head -c 100 \"$4/frame-00000.png\" > \"$3/frame-00000.png\" && \"$0\" render \"$1\" --engine embree --path \"$2\" --frames \"$3\" --fps 10 --width 64 --height 36 --spp 4 && cmp \"$3/frame-00002.png\" \"$4/frame-00000.png\" && cmp \"$3/frame-00000.png\" \"$4/frame-00000.png\" && cmp \"$3/frame-00003.png\" \"$4/frame-00003.png\" && ! ls -a \"$3\" | grep -q tmp"
  "${rp_dir}/resume_frames" "${rp_dir}/embree_frames")
set_tests_properties(render_path_resume PROPERTIES FIXTURES_REQUIRED "render_path_folder;render_path_embree_frames")
# Every frame there already: nothing rendered, the movie made again.
render_path_test(all_done "wrote .*embree_frames \\(4 frames of 64x36 at 10 frames/s with embree, 4 there already"
  "\"$0\" render \"$1\" --engine embree --path \"$2\" --frames \"$3\" --fps 10 --width 64 --height 36 --spp 4"
  "${rp_dir}/embree_frames")
set_tests_properties(render_path_all_done PROPERTIES FIXTURES_REQUIRED "render_path_folder;render_path_embree_frames"
                     DEPENDS "render_path_view_matches_embree;render_path_resume")

# POV-Ray through its animation clock: one run renders the 4 frames (its log: frames 1 .. 4 of 4,
# each frame parsed again in that run, as POV-Ray does); no temporary .pov or work folder left.
render_path_test(povray "Rendering frame 4 of 4"
  "rm -rf \"$3\" && \"$0\" --quiet render \"$1\" --engine povray --path \"$2\" --frames \"$3\" --fps 10 --width 64 --height 36 && test -s \"$3/frame-00003.png\" && test ! -e \"$3/frame-00004.png\" && test -s \"$3/path.mp4\" && test -z \"$(ls -a \"$3\" | grep tmp)\" && test -z \"$(ls -a \"$1\" | grep scene_path.pov)\" && grep -c 'Parse Time' \"$1/povray.log\" && grep 'Rendering frame' \"$1/povray.log\""
  "${rp_dir}/povray_frames")
set_tests_properties(render_path_povray PROPERTIES FIXTURES_SETUP render_path_povray_frames)
# POV-Ray resumed: with frames 1 and 2 there, its one run renders frames 0 and 3 alone (the camera
# array holds theirs), the same pictures as the run of every frame.
render_path_test(povray_resume "2 there already"
  "rm -rf \"$3\" && mkdir -p \"$3\" && cp \"$4/frame-00001.png\" \"$4/frame-00002.png\" \"$3/\" && \"$0\" render \"$1\" --engine povray --path \"$2\" --frames \"$3\" --fps 10 --width 64 --height 36 && sh \"$5\" \"$3/frame-00000.png\" \"$4/frame-00000.png\" 60 && sh \"$5\" \"$3/frame-00003.png\" \"$4/frame-00003.png\" 60"
  "${rp_dir}/povray_resume_frames" "${rp_dir}/povray_frames" "${psnr_at_least}")
set_tests_properties(render_path_povray_resume PROPERTIES FIXTURES_REQUIRED "render_path_folder;render_path_povray_frames")
# Blender: one run, the camera keyframed in FRAMES/path.blend, Cycles at 4 samples.
render_path_test(blender "rendered frame 1 in"
  "rm -rf \"$3\" && \"$0\" --quiet render \"$1\" --engine blender --path \"$2\" --frames \"$3\" --fps 5 --width 64 --height 36 --spp 4 && test -s \"$3/frame-00001.png\" && test ! -e \"$3/frame-00002.png\" && test -s \"$3/path.mp4\" && test -s \"$3/path.blend\" && test -z \"$(ls -a \"$3\" | grep tmp)\" && cat \"$3/blender.log\""
  "${rp_dir}/blender_frames")

# Refusals, each before a frames folder is made: a path file that is not there, a frame rate out
# of range, a frames folder that cannot be made (under a file), --frames without --path.
render_path_test(missing_path "nowhere.json"
  "rm -rf \"$3\"; \"$0\" --quiet render \"$1\" --engine embree --path \"$1/nowhere.json\" --frames \"$3\"; test $? = 1 && test ! -e \"$3\""
  "${rp_dir}/refused_frames")
render_path_test(bad_fps "--fps 0.5: expected 1 .. 240 frames a second"
  "rm -rf \"$3\"; \"$0\" --quiet render \"$1\" --engine embree --path \"$2\" --frames \"$3\" --fps 0.5; test $? = 1 && test ! -e \"$3\""
  "${rp_dir}/refused_frames")
render_path_test(frames_unwritable "cannot make the frames folder"
  "\"$0\" --quiet render \"$1\" --engine embree --path \"$2\" --frames \"$2/frames\" --width 64 --height 36; test $? = 1")
# A part of the path (a batch's task): frames 1 and 2 of 4, as POV-Ray renders them in the whole
# path's run (the same pixels), and no path.mp4; a part past the path's end is refused.
render_path_test(part "frames 1 .. 2; path.mp4 only for the whole path"
  "rm -rf \"$3\" && \"$0\" render \"$1\" --engine povray --path \"$2\" --frames \"$3\" --fps 10 --width 64 --height 36 --first-frame 1 --frame-count 2 && test \"$(ls \"$3\" | tr '\\n' ' ')\" = 'frame-00001.png frame-00002.png ' && idiff -q \"$3/frame-00002.png\" \"$4/frame-00002.png\" && \"$0\" --quiet render \"$1\" --engine povray --path \"$2\" --frames \"$3\" --fps 10 --first-frame 3 --frame-count 2; test $? = 1"
  "${rp_dir}/part_frames" "${rp_dir}/povray_frames")
set_tests_properties(render_path_part PROPERTIES FIXTURES_REQUIRED "render_path_folder;render_path_povray_frames"
                     RESOURCE_LOCK render_path_povray_log)
render_path_test(frames_without_path "--frames, --fps, --first-frame and --frame-count go with --path"
  "\"$0\" --quiet render \"$1\" --engine embree --frames \"$1/x\"; test $? = 2")

# --camera/--look-at: another camera without building again. Embree from a camera of the view's
# command line, the view's frame of it within a loose PSNR; POV-Ray from it too (a new picture,
# the temporary .pov gone).
render_path_test(camera_embree "PSNR [0-9.]+ dB"
  "\"$0\" --quiet render \"$1\" --engine embree --camera 3,-14 --look-at 0,0,1.0 --width 64 --height 36 --spp 4 --out \"$1/cam_embree.png\" && \"$0\" --quiet view \"$1\" --camera 3,-14 --look-at 0,0,1.0 --size 64x36 --out \"$1/cam_view.png\" && sh \"$3\" \"$1/cam_view.png\" \"$1/cam_embree.png\" 16.5"
  "${psnr_at_least}")
render_path_test(camera_povray "differ"
  "\"$0\" --quiet render \"$1\" --engine povray --width 64 --height 36 --out \"$1/own_povray.png\" && \"$0\" --quiet render \"$1\" --engine povray --camera 3,-14 --look-at 0,0,1.0 --width 64 --height 36 --out \"$1/cam_povray.png\" && test -z \"$(ls -a \"$1\" | grep scene_camera.pov)\" && ! cmp -s \"$1/own_povray.png\" \"$1/cam_povray.png\" && echo differ")
# POV-Ray under another sun (render --sun): another picture than under the scene's sun, the
# folder's scene.pov untouched, its mean colour within CIEDE2000 6 of Embree's under the same sun
# (measured 0.1 at 300, 10).
render_path_test(sun_povray "CIEDE2000"
  "\"$0\" --quiet render \"$1\" --engine povray --width 64 --height 36 --out \"$1/own_sun_povray.png\" && \"$0\" --quiet render \"$1\" --engine povray --width 64 --height 36 --sun 300,10 --out \"$1/sun_povray.png\" && test -s \"$1/own_sun_povray.png\" && ! cmp -s \"$1/own_sun_povray.png\" \"$1/sun_povray.png\" && grep -q 'Sun: azimuth 200.00' \"$1/scene.pov\" && \"$0\" --quiet render \"$1\" --engine embree --width 64 --height 36 --spp 4 --sun 300,10 --out \"$1/sun_embree.png\" && /usr/bin/python3 \"$3\" --limit 6 --bands 1 compare povray=\"$1/sun_povray.png\" embree=\"$1/sun_embree.png\" | sed 's/$/ CIEDE2000/'"
  "${PROJECT_SOURCE_DIR}/bench/band_colors.py")
# POV-Ray writes DIR/povray.log: its tests one at a time.
set_tests_properties(render_path_povray render_path_povray_resume render_path_camera_povray render_path_sun_povray
                     PROPERTIES RESOURCE_LOCK render_path_povray_log)
# Blender took 4.7 s for its 2 frames on idle cores (measured), 8.6 min on cores busy with other work.
set_tests_properties(render_path_blender PROPERTIES TIMEOUT 300)
