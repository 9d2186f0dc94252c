# Hostile inputs of issue 25 besides batch files (tests/cli/hostile_batch.cmake): LDI packs, ground
# exemplars, tile commands and scene files. Uses hostile_test() and hostile_dir of hostile.cmake.
hostile_test(ldi_fifo 1 "fifo.ldi: not a regular file"
             sh -c "rm -f \"$1\" && mkfifo \"$1\" && exec timeout 20 \"$0\" ldi info \"$1\""
             "${WANGSCAPE_BIN}" "${hostile_dir}/fifo.ldi")
