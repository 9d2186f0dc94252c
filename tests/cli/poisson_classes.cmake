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
# scatter --metrics per class: each class's row, no pair closer than its own spacing.
add_test(NAME scatter_metrics_per_class
  COMMAND ${cli_expect} 0 "^ +1 +[0-9]+ +[0-9.]+ +[0-9.]+ +0 < [0-9.]+ "
    sh -c "'${WANGSCAPE_BIN}' --quiet tileset --set cohen8 --per-tile 40 --class 0.7 --class 0.3:0.07 \
      --out '${CLI_SCRATCH}/classes_metrics.json' && '${WANGSCAPE_BIN}' scatter \
      --tileset '${CLI_SCRATCH}/classes_metrics.json' --plane 64x64 --tile-size 4 --metrics")
set_tests_properties(tileset_classes tileset_class_malformed tileset_classes_out_scatter scatter_metrics_per_class
  PROPERTIES LABELS cli)
