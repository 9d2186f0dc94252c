# wangscape render DIR --engine embree (issue 11 part 4): the Embree reference renderer on the
# tiny scene (built without exports: it renders the Scene made again from DIR/scene.toml).
set(embree_dir "${CLI_SCRATCH}/embree")
file(MAKE_DIRECTORY "${embree_dir}/src")
tiny_scene("${embree_dir}/embree_tiny.toml" EXPORTS "povray = false")

# --width/--height/--out: a 64 x 36 PNG where --out says (its IHDR gives the size).
add_test(NAME embree_render_size
  COMMAND ${cli_expect} 0 "0 +0 +0 +64 +0 +0 +0 +36"
          sh -c "rm -rf \"$1\" \"$1.png\" && \"$0\" --quiet build \"$1.toml\" --out \"$1\" && \"$0\" --quiet render \"$1\" --engine embree --width 64 --height 36 --out \"$1.png\" && od -An -tu1 -j16 -N8 \"$1.png\""
          "${WANGSCAPE_BIN}" "${embree_dir}/embree_tiny")
# Without --out: DIR/render_embree.png at the scene's size (96 x 72), the same bytes twice.
add_test(NAME embree_render_default_deterministic
  COMMAND ${cli_expect} 0 "0 +0 +0 +96 +0 +0 +0 +72"
          sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$2.toml\" --out \"$1\" && \"$0\" --quiet render \"$1\" --engine embree --spp 2 && cp \"$1/render_embree.png\" \"$1/first.png\" && \"$0\" --quiet render \"$1\" --engine embree --spp 2 && cmp \"$1/first.png\" \"$1/render_embree.png\" && od -An -tu1 -j16 -N8 \"$1/render_embree.png\""
          "${WANGSCAPE_BIN}" "${embree_dir}/embree_default" "${embree_dir}/embree_tiny")
# A scene file elsewhere with a relative path (a user mesh beside it): the folder remembers
# where that path resolves (DIR/scene_base.txt).
file(WRITE "${embree_dir}/src/stick.obj" "v 0 0 0\nv 0.2 0 0\nv 0 0 1.5\nusemtl stem\nf 1 2 3\n")
tiny_scene("${embree_dir}/src/relative.toml" MODELS "mesh = \"stick.obj\"" EXPORTS "povray = false")
add_test(NAME embree_render_relative_paths
  COMMAND sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$2\" --out \"$1\" && \"$0\" --quiet render \"$1\" --engine embree --width 32 --height 24 && test -s \"$1/render_embree.png\""
          "${WANGSCAPE_BIN}" "${embree_dir}/relative" "${embree_dir}/src/relative.toml")
# Refusals: a bad --spp names the flag; an unknown engine lists embree; --spp is embree's alone.
add_test(NAME embree_render_bad_spp
  COMMAND ${cli_expect} 2 "--spp"
          "${WANGSCAPE_BIN}" render "${embree_dir}/embree_tiny" --engine embree --spp 0)
add_test(NAME embree_render_unknown_engine
  COMMAND ${cli_expect} 1 "engine 'mitsuba' .*known: povray, blender, embree"
          "${WANGSCAPE_BIN}" render "${embree_dir}/embree_tiny" --engine mitsuba)
add_test(NAME embree_render_out_needs_embree
  COMMAND ${cli_expect} 1 "--spp is for --engine embree"
          "${WANGSCAPE_BIN}" render "${embree_dir}/embree_tiny" --engine povray --spp 4 --out "${embree_dir}/x.png")
# --height alone: the width keeps the scene's aspect (96 x 72: 24 high is 32 wide).
add_test(NAME embree_render_height_alone
  COMMAND ${cli_expect} 0 "0 +0 +0 +32 +0 +0 +0 +24"
          sh -c "\"$0\" --quiet render \"$1\" --engine embree --spp 1 --height 24 --out \"$1_h.png\" && od -An -tu1 -j16 -N8 \"$1_h.png\""
          "${WANGSCAPE_BIN}" "${embree_dir}/embree_tiny")
add_test(NAME embree_render_not_a_folder
  COMMAND ${cli_expect} 1 "no_such_folder: no such scene folder"
          "${WANGSCAPE_BIN}" render "${embree_dir}/no_such_folder" --engine embree)
# --sun and --fov (issue 39: batch's Embree stills use them): another sun and lens give another
# picture; a sun that is not two angles in range is refused naming the flag; Blender refuses them.
add_test(NAME embree_render_sun_and_fov
  COMMAND sh -c "\"$0\" --quiet render \"$1\" --engine embree --width 48 --out \"$1_a.png\" && \"$0\" --quiet render \"$1\" --engine embree --width 48 --sun 300,10 --out \"$1_b.png\" && \"$0\" --quiet render \"$1\" --engine embree --width 48 --fov 80 --out \"$1_c.png\" && ! cmp -s \"$1_a.png\" \"$1_b.png\" && ! cmp -s \"$1_a.png\" \"$1_c.png\""
          "${WANGSCAPE_BIN}" "${embree_dir}/embree_tiny")
add_test(NAME embree_render_bad_sun
  COMMAND ${cli_expect} 2 "--sun: '300,95' is not AZIMUTH,ELEVATION in degrees"
          "${WANGSCAPE_BIN}" render "${embree_dir}/embree_tiny" --engine embree --sun 300,95)
add_test(NAME embree_render_sun_needs_embree
  COMMAND ${cli_expect} 1 "--fov and --sun are for --engine embree and povray"
          "${WANGSCAPE_BIN}" render "${embree_dir}/embree_tiny" --engine blender --sun 300,10)
set_tests_properties(embree_render_bad_spp embree_render_unknown_engine embree_render_out_needs_embree
  embree_render_height_alone embree_render_sun_and_fov embree_render_bad_sun embree_render_sun_needs_embree
  PROPERTIES DEPENDS embree_render_size)
