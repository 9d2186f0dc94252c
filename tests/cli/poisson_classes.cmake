# wangscape tileset --class (issue 26), run for real: several classes fill one set and are
# reported per class, written and scattered; a malformed class is refused with one clear line.
add_test(NAME tileset_classes
  COMMAND ${cli_expect} 0 "2 +[0-9.]+ \\( +2\\.00\\).*\\(edge objects\\)"
    ${WANGSCAPE_BIN} --quiet tileset --set cohen8 --per-tile 40 --class 0.7 --class 0.25
    --class 0.05:0.08:0.06:edge --sheet ${CLI_SCRATCH}/classes_sheet.png)
add_test(NAME tileset_class_malformed
  COMMAND ${cli_expect} 1 "--class '0.7:x'; expected SHARE"
    ${WANGSCAPE_BIN} tileset --set cohen8 --per-tile 40 --class 0.7:x)
# The file keeps the classes (scene/filled_tileset_file) and scatter lays them: no pair closer
# than the union's packing diameter.
add_test(NAME tileset_classes_out_scatter
  COMMAND ${cli_expect} 0 "pairs < [0-9.]+ m: +0$"
    sh -c "'${WANGSCAPE_BIN}' --quiet tileset --set cohen8 --per-tile 40 --class 0.7 --class 0.3:0.07 --relax 4 \
      --out '${CLI_SCRATCH}/classes.json' && '${WANGSCAPE_BIN}' scatter --tileset '${CLI_SCRATCH}/classes.json' \
      --plane 64x64 --tile-size 4 --metrics")
# scatter --metrics per class: each class's row, no pair closer than its own spacing, its own
# spectrum's anisotropy off the tile grid last, not 0.00 (the false value the per-class metrics
# read without a spectrum of their own; -3.20 dB today).
add_test(NAME scatter_metrics_per_class
  COMMAND ${cli_expect} 0 "^ +1 +[0-9]+ +[0-9.]+ +[0-9.]+ +0 < [0-9.]+ +[0-9.]+ +[0-9.]+ +-?([1-9][0-9]*\\.[0-9]{2}|0\\.(0[1-9]|[1-9][0-9]))$"
    sh -c "'${WANGSCAPE_BIN}' --quiet tileset --set cohen8 --per-tile 40 --class 0.7 --class 0.3:0.07 \
      --out '${CLI_SCRATCH}/classes_metrics.json' && '${WANGSCAPE_BIN}' scatter \
      --tileset '${CLI_SCRATCH}/classes_metrics.json' --plane 64x64 --tile-size 4 --metrics")
# The same over a DEM, as JSON: a "classes" array, every class with points, no close pair and its
# own spectrum (600 m tiles: 23,099 points, about 2 s with the class spectra).
find_program(classes_python3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
add_test(NAME scatter_metrics_per_class_dem_json
  COMMAND ${cli_expect} 0 "^classes [0-9]+:[0-9.]+ [0-9]+:[0-9.]+ union [0-9]+$"
    sh -c "'${WANGSCAPE_BIN}' --quiet tileset --set cohen8 --per-tile 40 --class 0.7 --class 0.3:0.07 \
      --out '${CLI_SCRATCH}/classes_dem.json' > /dev/null && '${WANGSCAPE_BIN}' --quiet scatter \
      --tileset '${CLI_SCRATCH}/classes_dem.json' --dem '${PROJECT_SOURCE_DIR}/tests/data/dem/SRTMGL3_boulder_CO_240x144.asc' \
      --tile-size 600 --metrics --json > '${CLI_SCRATCH}/classes_dem_metrics.json' && \
      '${classes_python3}' '${CMAKE_CURRENT_SOURCE_DIR}/scatter_classes_check.py' '${CLI_SCRATCH}/classes_dem_metrics.json' 2")
set_tests_properties(tileset_classes tileset_class_malformed tileset_classes_out_scatter scatter_metrics_per_class
  scatter_metrics_per_class_dem_json
  PROPERTIES LABELS cli)
