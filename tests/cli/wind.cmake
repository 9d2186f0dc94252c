# [wind] (issue 39 part 4): the tiny field in a strong wind, built with the POV-Ray and Blender
# exports, rendered along a path that stands still for 0.3 s, so that only the wind moves the
# picture. Frame k of POV-Ray and of Blender against Embree's frame k and another frame (measured
# at 96 x 54: POV-Ray 24.3 dB at the same time, 21.4 at another; Cycles at 8 samples 20.6 and
# 19.4): every engine sways the same plants the same way at the same time. A wind of strength 0
# writes what no [wind] writes, byte for byte.
set(wind_dir "${CLI_SCRATCH}/wind")
file(MAKE_DIRECTORY "${wind_dir}")
set(wind_section "[wind]\ndirection = 90\nstrength = 20\ngust_scale = 6\nspeed = 6")
tiny_scene("${wind_dir}/windy.toml" EXPORTS "povray = true\nblender = true\n${wind_section}")
tiny_scene("${wind_dir}/calm.toml" EXPORTS "povray = true\nblender = true")
set(wind_ldi "ldi = true\n[ldi]\nlevels = 2\ndirections = 2\nsky_rays = 0")
tiny_scene("${wind_dir}/windy_ldi.toml" EXPORTS "povray = false\n${wind_ldi}\n${wind_section}")
tiny_scene("${wind_dir}/calm_ldi.toml" EXPORTS "povray = false\n${wind_ldi}")
tiny_scene("${wind_dir}/still_air.toml" EXPORTS "povray = true\nblender = true\n[wind]\nstrength = 0")
file(WRITE "${wind_dir}/stand.json"
  "{\"keyframes\": [{\"time\": 0, \"position\": [0, -16], \"height_above_ground\": 2.2, \"look_at\": [0, 0], \"look_at_height_above_ground\": 1.2},\n"
  "                {\"time\": 0.3, \"position\": [0, -16], \"height_above_ground\": 2.2, \"look_at\": [0, 0], \"look_at_height_above_ground\": 1.2}]}\n")
set(wind_check "${CMAKE_CURRENT_LIST_DIR}/wind_frames_check.sh")

add_test(NAME wind_build
  COMMAND ${cli_expect} 0 "Wind_North" sh -c "rm -rf \"$1/windy\" && \"$0\" --quiet build \"$1/windy.toml\" --out \"$1/windy\" && grep -c 'rotate<Wind_North(' \"$1/windy/instances.inc\" && grep -q '\"wind\"' \"$1/windy/blender/manifest.json\" && cat \"$1/windy/scene.pov\""
          "${WANGSCAPE_BIN}" "${wind_dir}")
set_tests_properties(wind_build PROPERTIES LABELS "cli;wind" TIMEOUT 300 FIXTURES_SETUP wind_folder)

# Embree, frame by frame over one build, each frame's flowers leaned anew.
add_test(NAME wind_embree_frames
  COMMAND ${cli_expect} 0 "4 frames of 96x54" sh -c "rm -rf \"$1/embree\" && \"$0\" render \"$1/windy\" --engine embree --path \"$1/stand.json\" --frames \"$1/embree\" --fps 10 --width 96 --height 54 --spp 4 && ! cmp -s \"$1/embree/frame-00000.png\" \"$1/embree/frame-00003.png\""
          "${WANGSCAPE_BIN}" "${wind_dir}")
set_tests_properties(wind_embree_frames PROPERTIES LABELS "cli;wind" TIMEOUT 300 FIXTURES_REQUIRED wind_folder
                     FIXTURES_SETUP wind_embree)

# POV-Ray through its clock: frames 0 and 3 against Embree's frames 0 and 3, each against the other.
add_test(NAME wind_povray_sways_as_embree
  COMMAND ${cli_expect} 0 "PSNR" sh -c "rm -rf \"$1/povray\" && \"$0\" --quiet render \"$1/windy\" --engine povray --path \"$1/stand.json\" --frames \"$1/povray\" --fps 10 --width 96 --height 54 && sh \"$2\" \"$1/povray/frame-00003.png\" \"$1/embree/frame-00003.png\" \"$1/embree/frame-00000.png\" 23 1.5 && sh \"$2\" \"$1/povray/frame-00000.png\" \"$1/embree/frame-00000.png\" \"$1/embree/frame-00003.png\" 23 1.5"
          "${WANGSCAPE_BIN}" "${wind_dir}" "${wind_check}")
set_tests_properties(wind_povray_sways_as_embree PROPERTIES LABELS "cli;wind" TIMEOUT 300
                     FIXTURES_REQUIRED "wind_folder;wind_embree")

# Blender: geometry nodes of the scene time; its frame 1 at 5 frames/s is Embree's frame 2 at 10.
add_test(NAME wind_blender_sways_as_embree
  COMMAND ${cli_expect} 0 "PSNR" sh -c "rm -rf \"$1/blender\" && \"$0\" --quiet render \"$1/windy\" --engine blender --path \"$1/stand.json\" --frames \"$1/blender\" --fps 5 --width 96 --height 54 --spp 8 && sh \"$2\" \"$1/blender/frame-00001.png\" \"$1/embree/frame-00002.png\" \"$1/embree/frame-00000.png\" 19.5 0.5"
          "${WANGSCAPE_BIN}" "${wind_dir}" "${wind_check}")
set_tests_properties(wind_blender_sways_as_embree PROPERTIES LABELS "cli;wind" TIMEOUT 300
                     FIXTURES_REQUIRED "wind_folder;wind_embree")

# Calm: strength 0 writes the very files of a scene without [wind].
add_test(NAME wind_calm_is_unchanged
  COMMAND ${cli_expect} 0 "same" sh -c "rm -rf \"$1/calm\" \"$1/still_air\" && \"$0\" --quiet build \"$1/calm.toml\" --out \"$1/calm\" && \"$0\" --quiet build \"$1/still_air.toml\" --out \"$1/still_air\" && for f in scene.pov instances.inc models.inc terrain.inc blender/manifest.json blender/instances_x.f32; do cmp \"$1/calm/$f\" \"$1/still_air/$f\" || exit 1; done && ! grep -q Wind \"$1/calm/scene.pov\" && echo same"
          "${WANGSCAPE_BIN}" "${wind_dir}")
set_tests_properties(wind_calm_is_unchanged PROPERTIES LABELS "cli;wind" TIMEOUT 300)

# The view leaves the wind out (its LDIs are a tile's, shared by every place the tile lies): a
# windy folder's frame, near field included, is the calm folder's, byte for byte; the Embree still
# of the same camera does lean.
add_test(NAME wind_view_stands_still
  COMMAND ${cli_expect} 0 "calm view" sh -c "rm -rf \"$1/windy_ldi\" \"$1/calm_ldi\" && \"$0\" --quiet build \"$1/windy_ldi.toml\" --out \"$1/windy_ldi\" && \"$0\" --quiet build \"$1/calm_ldi.toml\" --out \"$1/calm_ldi\" && for f in windy_ldi calm_ldi; do \"$0\" --quiet view \"$1/$f\" --size 96x54 --out \"$1/$f/view.png\" && \"$0\" --quiet render \"$1/$f\" --engine embree --width 96 --height 54 --spp 1 --out \"$1/$f/embree.png\" || exit 1; done && cmp \"$1/windy_ldi/view.png\" \"$1/calm_ldi/view.png\" && ! cmp -s \"$1/windy_ldi/embree.png\" \"$1/calm_ldi/embree.png\" && echo calm view"
          "${WANGSCAPE_BIN}" "${wind_dir}")
set_tests_properties(wind_view_stands_still PROPERTIES LABELS "cli;wind" TIMEOUT 300)
