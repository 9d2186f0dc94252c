# What the third hostile probe still found (issue 41, "What the probe still finds"): each case is
# refused at once with exit 1 (2 for flags), a message naming the file and line, or the flag, and
# what was expected, and leaves nothing behind. Uses hostile_test() of hostile.cmake and the view's
# folder of view.cmake (CMake globs the *.cmake files in sorted order: hostile.cmake comes first).
set(probe_dir "${CLI_SCRATCH}/hostile_probe")
file(MAKE_DIRECTORY "${probe_dir}")
set(probe_view_folder "${CLI_SCRATCH}/view/field")  # built by cli_view_build (fixture view_folder)
set(cli_refuse sh "${CMAKE_CURRENT_SOURCE_DIR}/refuse.sh")

# probe_test(NAME CODE REGEX COMMAND...): refuse.sh (exit CODE, REGEX, no library text, 30 s).
function(probe_test name code regex)
  add_test(NAME hostile_probe_${name} COMMAND ${cli_refuse} ${code} "${regex}" ${ARGN})
  set_tests_properties(hostile_probe_${name} PROPERTIES LABELS "cli;hostile" TIMEOUT 60)
endfunction()

# Kind 2: memory estimated before it is allocated, naming the key or the flag and the limit. A flat
# field of 10^6 m a side held its scanline tiling whole (125 GB); a view frame of 16384 x 16384
# pixels under a 4 GB address-space limit failed after 26 s with a generic out-of-memory line.
file(WRITE "${probe_dir}/flat_1e6.toml" "[terrain]\nflat_size = 1000000.0\n[models]\nvariants = 1\ntriangle_budget = 400\n")
probe_test(flat_field_memory 0 "flat_1e6.toml:2: 'terrain.flat_size' gives a field of 250001 x 250001 tiles of 4 m, whose placed-tile grid and scanline tiling \\(3 bytes a tile\\) would need about 187.50 GB of memory. the limit is [0-9.]+ GB .*tiles.algorithm = \"hash\""
           sh -c "rm -rf \"$1\" && ! \"$0\" build \"$2\" --out \"$1\" && test ! -e \"$1\" && ! ls -a \"$(dirname \"$1\")\" | grep -q '^[.]flat_out[.]'"
           "${WANGSCAPE_BIN}" "${probe_dir}/flat_out" "${probe_dir}/flat_1e6.toml")
probe_test(view_size_memory 0 "--size 16384x16384: frames of 268435456 pixels at about [0-9]+ bytes a pixel .* would need about [0-9.]+ GB of memory. the limit is 2.00 GB .*lower --size"
           sh -c "rm -f \"$1\" && ! prlimit --as=4000000000 \"$0\" view \"$2\" --size 16384x16384 --out \"$1\" && test ! -e \"$1\""
           "${WANGSCAPE_BIN}" "${probe_dir}/big_frame.png" "${probe_view_folder}")
probe_test(view_compare_memory 1 "--size 16384x16384: frames of 268435456 pixels at about [0-9]+ bytes a pixel \\([0-9]+ threads, the comparison\\) would need about [0-9.]+ GB of memory"
           "${WANGSCAPE_BIN}" view "${probe_view_folder}" --size 16384x16384 --compare)
set_tests_properties(hostile_probe_view_size_memory hostile_probe_view_compare_memory PROPERTIES FIXTURES_REQUIRED view_folder)
set_property(TEST hostile_probe_view_size_memory APPEND PROPERTY LABELS address-space-limit)

# Kind 5: messages that name the file or flag and what was expected.
# A GeoTIFF whose center lies at latitude 99.97: the DEM is named (it was only "origin latitude ...").
probe_test(dem_latitude_out_of_range 1 "^wangscape: error: .*lat_99.tif: its center lies at latitude 99.970000, longitude 10.040000 \\(WGS 84 degrees\\). expected latitude in \\[-90, 90\\]"
           sh -c "rm -f \"$1\" && gdal_create -q -of GTiff -outsize 8 6 -ot Float32 -a_srs EPSG:4326 -a_ullr 10 100 10.08 99.94 \"$1\" && exec \"$0\" terrain info \"$1\""
           "${WANGSCAPE_BIN}" "${probe_dir}/lat_99.tif")
# A path keyframe looking at its own eye: the file and the keyframe (it was the renderer's "the
# camera must look somewhere sideways").
file(WRITE "${probe_dir}/look_at_eye.json"
  "{\"keyframes\": [{\"time\": 0, \"position\": [0, -16, 2.2], \"look_at\": [0, -16, 2.2]},\n"
  "                {\"time\": 0.3, \"position\": [2, -10, 2.0], \"look_at\": [0, 4, 1.0]}]}\n")
probe_test(path_look_at_eye 1 "look_at_eye.json:keyframes\\[0\\].look_at: is straight above, below or at the position"
           "${WANGSCAPE_BIN}" view "${probe_view_folder}" --path "${probe_dir}/look_at_eye.json" --stats --size 32x24)
# An output file that is a folder: refused as a flag before the work (it was "rename failed" after).
file(MAKE_DIRECTORY "${probe_dir}/a_folder.png")
probe_test(view_out_is_folder 2 "--out: '.*a_folder.png' is a folder. name a file to write"
           "${WANGSCAPE_BIN}" view "${probe_view_folder}" --size 32x24 --out "${probe_dir}/a_folder.png")
probe_test(tiling_out_is_folder 2 "--out: '.*a_folder.png' is a folder. name a file to write"
           "${WANGSCAPE_BIN}" tiling --set cohen8 --size 4x4 --out "${probe_dir}/a_folder.png")
probe_test(tileset_sheet_is_folder 2 "--sheet: '.*a_folder.png' is a folder. name a file to write"
           "${WANGSCAPE_BIN}" tileset --set cohen8 --sheet "${probe_dir}/a_folder.png")
# --fps below 1 frame/s: refused before the frames (ffmpeg failed afterwards while the range was (0, 240]).
probe_test(view_fps_tiny 1 "--fps 1e-300: expected 1 .. 240 frames per second"
           "${WANGSCAPE_BIN}" view "${probe_view_folder}" --path "${CLI_SCRATCH}/view/path.json" --frames "${probe_dir}/fps_frames" --fps 1e-300)
# --chunk 0: the range's real bounds (CLI11's PositiveNumber printed the largest double, 309 digits).
probe_test(batch_chunk_zero 2 "^--chunk: Value 0 not in range 1 to 100000$"
           "${WANGSCAPE_BIN}" batch run "${probe_dir}/none.toml" --out "${probe_dir}/chunk" --chunk 0)
probe_test(scatter_max_instances_zero 2 "^--max-instances: Value 0 not in range 1 to 1000000000000000$"
           "${WANGSCAPE_BIN}" scatter --tileset "${probe_dir}/none.json" --max-instances 0)
set_tests_properties(hostile_probe_path_look_at_eye hostile_probe_view_out_is_folder hostile_probe_view_fps_tiny
                     PROPERTIES FIXTURES_REQUIRED view_folder)

# Kind 6: an LDI frame beyond its level and its tile's prism. Checked for finiteness only, each of
# these passed `ldi info` (exit 0) and the view drew from it. ldi_frame.py overwrites one field
# of tile 5's frame (level 0, direction 1) in a copy of the pack ldi.cmake builds.
set(probe_ldi "${CLI_SCRATCH}/ldi/tiny.ldi")  # built by cli_ldi_build (fixture ldi_pack)
set(probe_ldi_place "frame_([a-z_]+).ldi:LDI \\(tile 5, level 0, direction 1\\): its")
# probe_ldi_frame(NAME REGEX FIELD VALUE...): `ldi info` on the copy exits 1 naming the pack, the LDI and REGEX.
function(probe_ldi_frame name regex field)
  probe_test(ldi_frame_${name} 1 "^wangscape: error: .*${probe_ldi_place} ${regex}"
             sh -c "pack=\"$1\" script=\"$2\" out=\"$3\" && shift 3 && python3 \"$script\" \"$pack\" \"$out\" 5 0 1 \"$@\" && exec \"$0\" ldi info \"$out\""
             "${WANGSCAPE_BIN}"
             "${probe_ldi}" "${CMAKE_CURRENT_SOURCE_DIR}/ldi_frame.py" "${probe_dir}/frame_${name}.ldi" ${field} ${ARGN})
  set_tests_properties(hostile_probe_ldi_frame_${name} PROPERTIES FIXTURES_REQUIRED ldi_pack)
endfunction()
probe_ldi_frame(right_zero "frame's right axis \\(0, 0, 0\\) has length 0. expected a unit vector" right 0 0 0)
probe_ldi_frame(pixel_huge "pixel size 1e\\+30 m is not the level's 0.0092[0-9]* m \\(4 m / 4[0-9]+ pixels\\)" pixel_size 1e30)
probe_ldi_frame(origin_far "origin \\(1e\\+30, 1, 1\\) lies 1e\\+30 m from the centre of the tile's prism. expected within [0-9.]+ m"
                origin 1e30 1 1)
probe_ldi_frame(too_wide "size 65535 x [0-9]+ pixels is more than the tile's prism spans at 4[0-9]+ pixels a tile side \\(at most [0-9]+ a side\\)"
                width 65535)
# The view refuses such a pack as `ldi info` does, exit 1, and writes no frame: a copy of the
# view's folder whose tiles.ldi has tile 5's right axis zeroed.
probe_test(view_ldi_frame_right_zero 1 "^wangscape: error: .*frame_view/tiles.ldi:LDI \\(tile 5, level 0, direction 1\\): its frame's right axis \\(0, 0, 0\\) has length 0. expected a unit vector"
           sh -c "rm -rf \"$1\" && mkdir -p \"$1\" && cp -r \"$2\"/. \"$1\" && python3 \"$3\" \"$2/tiles.ldi\" \"$1/tiles.ldi\" 5 0 1 right 0 0 0 || exit 9
             \"$0\" view \"$1\" --size 32x24 --out \"$1/x.png\" || (code=$? && test ! -e \"$1/x.png\" || exit 9 && exit $code)"
           "${WANGSCAPE_BIN}" "${probe_dir}/frame_view" "${probe_view_folder}" "${CMAKE_CURRENT_SOURCE_DIR}/ldi_frame.py")
set_tests_properties(hostile_probe_view_ldi_frame_right_zero PROPERTIES FIXTURES_REQUIRED view_folder)

# Kind 7: --camera and --look-at beyond +-1e7 m, as the scene and path files refuse them (the
# view drew empty sky and exited 0): exit 1 as the view's other range checks, naming the flag, the
# value and the range, before the folder loads, and no frame written.
foreach(flag camera look-at)
  probe_test(view_${flag}_far 1 "^wangscape: error: --${flag} 1e\\+15,1e\\+15,1400: expected each of E, N, H within -1e\\+07 .. 1e\\+07 meters of the scene's origin$"
             sh -c "rm -f \"$1\" && \"$0\" view \"$2\" --${flag} 1e15,1e15,1400 --size 32x24 --out \"$1\" || (code=$? && test ! -e \"$1\" || exit 9 && exit $code)"
             "${WANGSCAPE_BIN}" "${probe_dir}/far_${flag}.png" "${probe_view_folder}")
endforeach()
probe_test(view_camera_far_ground 1 "^wangscape: error: --camera 0,-1e\\+08: expected each of E, N, H within"
           "${WANGSCAPE_BIN}" view "${probe_view_folder}" --camera 0,-1e8 --size 32x24 --stats --repeat 1)
set_tests_properties(hostile_probe_view_camera_far hostile_probe_view_look-at_far hostile_probe_view_camera_far_ground
                     PROPERTIES FIXTURES_REQUIRED view_folder)

# Kind 8: tiles that cannot be written (a file-size limit of 1 KB) leave no folder, not even an
# empty one, and no staging folder beside it (noise tiles left an empty folder): exit 1, the file
# named. The tiles are staged beside the folder and published by a rename (core/staged_folder.h).
foreach(kind noise texture)
  set(exemplar "")
  if(kind STREQUAL "texture")
    set(exemplar "--exemplar meadow --size 32")
  endif()
  probe_test(${kind}_tiles_unwritable 1 "^wangscape: error: cannot write '[^']*/${kind}_unwritable/${kind}_tile_0.png': write failed"
             bash -c "rm -rf \"$1\" && ulimit -f 1 && \"$0\" ${kind} tiles ${exemplar} --out \"$1\" || (code=$? && test ! -e \"$1\" && ! ls -a \"$(dirname \"$1\")\" | grep -q '^[.]${kind}_unwritable[.]' || exit 9 && exit $code)"
             "${WANGSCAPE_BIN}" "${probe_dir}/${kind}_unwritable")
endforeach()
probe_test(tiling_unwritable 1 "^wangscape: error: cannot write '[^']*/tiling_unwritable.png': write failed"
           bash -c "rm -f \"$1\" && ulimit -f 1 && \"$0\" tiling --set cohen8 --size 64x64 --out \"$1\" || (code=$? && test ! -e \"$1\" && ! ls -a \"$(dirname \"$1\")\" | grep -q '^[.]tiling_unwritable[.]' || exit 9 && exit $code)"
           "${WANGSCAPE_BIN}" "${probe_dir}/tiling_unwritable.png")
# An existing folder that holds other files is refused before the work (the tiles replace the folder whole).
probe_test(noise_tiles_other_folder 1 "^wangscape: error: .*/other_folder: exists and is not a folder of tiles \\(it has no noise_tiles.json\\). give a new or empty folder, or an earlier run's$"
           sh -c "rm -rf \"$1\" && mkdir -p \"$1\" && touch \"$1/keep\" && \"$0\" noise tiles --out \"$1\" || (code=$? && test -e \"$1/keep\" || exit 9 && exit $code)"
           "${WANGSCAPE_BIN}" "${probe_dir}/other_folder")
