# Hostile runs (issue 14, defects 4, 5, 7-10): interrupts, a full disk, paths POV-Ray cannot
# take, DEMs across the antimeridian, a camera under the ground, control characters in names,
# rasters too large for memory. Uses hostile_test() and hostile_dir of hostile.cmake (CMake
# globs the *.cmake files in sorted order: hostile.cmake comes first).
set(run_dir "${CLI_SCRATCH}/hostile_run")
file(MAKE_DIRECTORY "${run_dir}")
set(interrupt sh "${CMAKE_CURRENT_SOURCE_DIR}/interrupt.sh")
tiny_scene("${run_dir}/pov.toml" EXPORTS "povray = true")

# SIGINT / SIGTERM while writing: exit 130 / 143, no temporary left, a dead run's removed (the
# scatter is estimated at 2.4 GB, hence --yes: it is stopped long before).
tiny_scene("${run_dir}/big_field.toml" TILES "" EXPORTS "povray = true\ngltf = true")
file(READ "${run_dir}/big_field.toml" big_field)
# About 5.8 million flowers over flat ground of 800 m: long enough that the signal always lands
# before the build ends, even on an idle machine (1.4 million could finish first).
string(REPLACE "flat_size = 120.0" "flat_size = 800.0" big_field "${big_field}")
string(REPLACE "area = [-12.0, -12.0, 12.0, 12.0]" "area = [-400.0, -400.0, 400.0, 400.0]" big_field "${big_field}")
string(REPLACE "points_per_tile = 10" "points_per_tile = 60" big_field "${big_field}")
file(WRITE "${run_dir}/big_field.toml" "${big_field}")
hostile_test(interrupt_tiling_sigint 0 "SIGINT -> exit 130"
             ${interrupt} INT 130 "${run_dir}/tiling" ".*tmp-*"
             "${WANGSCAPE_BIN}" --quiet tiling --set cohen8 --size 12000x12000 --out "${run_dir}/tiling/big.csv")
hostile_test(interrupt_scatter_sigterm 0 "SIGTERM -> exit 143"
             sh -c "\"$0\" --quiet tileset --set cohen8 --per-tile 5 --out \"$1/filled.json\" >/dev/null && exec $2 TERM 143 \"$1/scatter\" '.*tmp-*' \"$0\" --quiet scatter --tileset \"$1/filled.json\" --plane 3000x3000 --tile-size 1 --yes --out \"$1/scatter/p.csv\""
             "${WANGSCAPE_BIN}" "${run_dir}" "sh ${CMAKE_CURRENT_SOURCE_DIR}/interrupt.sh")
hostile_test(interrupt_build_sigterm 0 "SIGTERM -> exit 143"
             ${interrupt} TERM 143 "${run_dir}/build" ".out.partial-*"
             "${WANGSCAPE_BIN}" --quiet build "${run_dir}/big_field.toml" --out "${run_dir}/build/out")
# During a POV-Ray render: POV-Ray is stopped too, its temporary image and state file removed.
hostile_test(interrupt_render_sigterm 0 "SIGTERM -> exit 143"
             sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$2\" --out \"$1\" && exec $3 TERM 143 \"$1\" '.*tmp-*' \"$0\" --quiet render \"$1\" --width 1600 --height 1200"
             "${WANGSCAPE_BIN}" "${run_dir}/render" "${run_dir}/pov.toml" "sh ${CMAKE_CURRENT_SOURCE_DIR}/interrupt.sh")
# SIGKILL during a POV-Ray render: no cleanup runs, and what stays is hidden temporaries whose
# names do not end in .png (POV-Ray writes its image to stdout; given a name it appends .png).
set(kill_check "sh ${CMAKE_CURRENT_SOURCE_DIR}/kill_leaves_no_content.sh")
hostile_test(kill_render_leaves_no_png 0 "no [*][.]png"
             sh -c "rm -rf \"$1\" && \"$0\" --quiet build \"$2\" --out \"$1\" && exec $3 \"$1\" '.*tmp-*' .png \"$0\" --quiet render \"$1\" --width 1600 --height 1200"
             "${WANGSCAPE_BIN}" "${run_dir}/render_kill" "${run_dir}/pov.toml" "${kill_check}")

# A full disk (the file-size limit) during a PNG: an error naming the file, nothing published.
# (No ';' in these scripts: CMake would split the argument there.)
hostile_test(png_disk_full 1 "cannot write '.*/m.png': write failed"
             sh -c "rm -f \"$1\"/m.png \"$1\"/.tmp-* \"$1\"/.*.tmp-*
                    prlimit --fsize=2000 \"$0\" tiling --set cohen8 --size 512x512 --out \"$1/m.png\"
                    code=$?
                    if ls -a \"$1\" | grep 'm.png'
                    then echo 'published a PNG' && exit 9
                    fi
                    exit $code"
             "${WANGSCAPE_BIN}" "${run_dir}")

# POV-Ray renders from a folder with a space and a ';' (made by printf '\073'); a newline
# in the folder is refused, and no staging folder of its own stays (other tests stage theirs in
# the same folder meanwhile).
hostile_test(povray_folder_with_space 0 "rendered"
             sh -c "d=\"$1$(printf '\\073')x\" && rm -rf \"$d\" && \"$0\" --quiet build \"$2\" --out \"$d\" && \"$0\" --quiet render \"$d\" --width 32 --height 24 && test -s \"$d/render.png\" && echo rendered"
             "${WANGSCAPE_BIN}" "${run_dir}/a folder" "${run_dir}/pov.toml")
hostile_test(povray_folder_with_newline 1 "POV-Ray cannot use this path: it holds a control character"
             sh -c "\"$0\" --quiet build \"$2\" --out \"$1/o
x\"
                    code=$?
                    if test -n \"$(find \"$1\" -maxdepth 1 -name '.o?x.partial-*')\"
                    then exit 9
                    fi
                    exit $code"
             "${WANGSCAPE_BIN}" "${run_dir}" "${run_dir}/pov.toml")

# A geographic DEM across 180 degrees: refused naming the file and what to do.
hostile_test(dem_antimeridian 1 "antimeridian_8x6.asc: the DEM spans longitudes 179.9850 to 180.0250, across the antimeridian.*gdalwarp"
             "${WANGSCAPE_BIN}" terrain info "${PROJECT_SOURCE_DIR}/tests/data/dem/edge-cases/antimeridian_8x6.asc")

# A camera below the ground.
tiny_scene("${run_dir}/below.toml")
file(READ "${run_dir}/below.toml" below)
string(REPLACE "position = [0.0, -16.0, 2.2]" "position = [0.0, -16.0, -3.0]" below "${below}")
file(WRITE "${run_dir}/below.toml" "${below}")
hostile_test(camera_below_ground 1 "below.toml:[0-9]+: 'camera.position' puts the camera 3 m below the ground"
             "${WANGSCAPE_BIN}" build "${run_dir}/below.toml" --out "${run_dir}/below_out")

# Control characters of a tile-set name are escaped on the terminal (no raw ESC or BEL).
file(WRITE "${run_dir}/evil.json"
     "{\"name\": \"evil\\u001b[31mRED\\u0007\", \"kind\": \"edge\", \"tiles\": [{\"n\":0,\"e\":0,\"s\":0,\"w\":0}]}\n")
hostile_test(tileset_name_escaped 0 "name: +evil\\\\x1b\\[31mRED\\\\x07"
             sh -c "if \"$0\" tileset --set \"$1\" | grep -q \"$(printf '[\\033\\007]')\"
                    then echo 'raw control characters' && exit 9
                    fi
                    exec \"$0\" tileset --set \"$1\""
             "${WANGSCAPE_BIN}" "${run_dir}/evil.json")

# Rasters estimated before they are read: a sparse 100000 x 100000 GeoTIFF DEM (a few KB on
# disk, 40 GB as heights) and a 30000 x 30000 RGBA mask (15 GB while read).
hostile_test(dem_too_large 1 "huge.tif: its 100000 x 100000 heights would need about 40.00 GB of memory; the limit is"
             sh -c "rm -f \"$1\" && gdal_create -q -of GTiff -outsize 100000 100000 -ot Float32 -co SPARSE_OK=TRUE -co TILED=YES -a_srs EPSG:32610 -a_ullr 500000 5100000 600000 5000000 \"$1\" && exec \"$0\" terrain info \"$1\""
             "${WANGSCAPE_BIN}" "${run_dir}/huge.tif")
file(WRITE "${run_dir}/huge_mask.toml"
     "[terrain]\ndem = \"${PROJECT_SOURCE_DIR}/data/SainteHelens.dem\"\n[masks]\nmask = \"huge_mask.tif\"\n[models]\nvariants = 1\ntriangle_budget = 400\n")
hostile_test(mask_too_large 1 "huge_mask.tif: the mask image of 30000 x 30000 pixels would need about 15.30 GB of memory"
             sh -c "rm -f \"$1\" && gdal_create -q -of GTiff -outsize 30000 30000 -bands 4 -ot Byte -co SPARSE_OK=TRUE -co TILED=YES \"$1\" && exec \"$0\" build \"$2\" --out \"$3\""
             "${WANGSCAPE_BIN}" "${run_dir}/huge_mask.tif" "${run_dir}/huge_mask.toml" "${run_dir}/huge_mask_out")

# Runaway fills: points_per_tile above what finishes, a set whose fill is estimated above a minute.
file(WRITE "${run_dir}/many_points.toml" "[terrain]\nflat_size = 20.0\n[tiles]\npoints_per_tile = 100000\n")
hostile_test(points_per_tile_too_many 1 "many_points.toml:4: 'tiles.points_per_tile' must be between 1 and 10000"
             "${WANGSCAPE_BIN}" build "${run_dir}/many_points.toml" --out "${run_dir}/many_points_out")
hostile_test(fill_too_long 1 "filling 4096 tiles with 20 points each .* would take about [0-9]+ s. at most 60 s are accepted"
             "${WANGSCAPE_BIN}" tileset --set complete-edge-8 --per-tile 20)

# scatter --metrics holds every point: estimated against the memory limit before placing, which
# an address-space limit lowers (prlimit --as; ASan's shadow memory cannot start under one).
hostile_test(scatter_metrics_memory 1 "filled.json: scatter --metrics over about 3.6e\\+07 instances would need about 1.01 GB of memory. the limit is 0.75 GB"
             sh -c "\"$0\" --quiet tileset --set cohen8 --per-tile 5 --out \"$1/filled.json\" >/dev/null && exec prlimit --as=1500000000 \"$0\" scatter --tileset \"$1/filled.json\" --plane 3000x3000 --tile-size 1 --metrics"
             "${WANGSCAPE_BIN}" "${run_dir}")
set_property(TEST hostile_scatter_metrics_memory APPEND PROPERTY LABELS address-space-limit)
