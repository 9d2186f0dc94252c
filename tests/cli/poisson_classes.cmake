# wangscape tileset --class (issue 26), run for real: several classes fill one set and are
# reported per class; a malformed class and --out with classes are refused with one clear line.
add_test(NAME tileset_classes
  COMMAND ${cli_expect} 0 "2 +[0-9.]+ \\( +2\\.00\\).*\\(edge objects\\)"
    ${WANGSCAPE_BIN} --quiet tileset --set cohen8 --per-tile 40 --class 0.7 --class 0.25
    --class 0.05:0.08:0.06:edge --sheet ${CLI_SCRATCH}/classes_sheet.png)
add_test(NAME tileset_class_malformed
  COMMAND ${cli_expect} 1 "--class '0.7:x'; expected SHARE"
    ${WANGSCAPE_BIN} tileset --set cohen8 --per-tile 40 --class 0.7:x)
add_test(NAME tileset_class_out_refused
  COMMAND ${cli_expect} 1 "--class with --out: the filled tile-set file"
    ${WANGSCAPE_BIN} tileset --set cohen8 --per-tile 40 --class 0.7 --out ${CLI_SCRATCH}/classes.json)
set_tests_properties(tileset_classes tileset_class_malformed tileset_class_out_refused PROPERTIES LABELS cli)
