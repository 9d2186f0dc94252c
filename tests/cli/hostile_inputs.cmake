# Hostile inputs of issue 25 besides batch files (tests/cli/hostile_batch.cmake): LDI packs, ground
# exemplars, tile commands and scene files. Uses hostile_test() and hostile_dir of hostile.cmake.
hostile_test(ldi_fifo 1 "fifo.ldi: not a regular file"
             sh -c "rm -f \"$1\" && mkfifo \"$1\" && exec timeout 20 \"$0\" ldi info \"$1\""
             "${WANGSCAPE_BIN}" "${hostile_dir}/fifo.ldi")
set(cli_refuse sh "${CMAKE_CURRENT_SOURCE_DIR}/refuse.sh")  # expect.sh, and no raw library text

# Ground exemplars of texture tiles: not a file, too large to decode (the estimate from the PNG's
# header, before decoding), damaged (libpng's own line never reaches the terminal).
add_test(NAME hostile_exemplar_dev_zero COMMAND ${cli_refuse} 1 "cannot read image '/dev/zero': not a regular file"
         "${WANGSCAPE_BIN}" texture tiles --exemplar /dev/zero --out "${hostile_dir}/exemplar_zero")
add_test(NAME hostile_exemplar_fifo COMMAND ${cli_refuse} 1 "fifo.png': not a regular file"
         sh -c "rm -f \"$1\" && mkfifo \"$1\" && exec \"$0\" texture tiles --exemplar \"$1\" --out \"$2\""
         "${WANGSCAPE_BIN}" "${hostile_dir}/fifo.png" "${hostile_dir}/exemplar_fifo")
# png.py W H FILE: a PNG header declaring W x H RGB pixels with one short IDAT chunk.
file(WRITE "${hostile_dir}/png.py" [=[
import struct, sys, zlib
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
w, h = int(sys.argv[1]), int(sys.argv[2])
ihdr = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
open(sys.argv[3], "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\0" * 100)) + chunk(b"IEND", b""))
]=])
add_test(NAME hostile_exemplar_huge
         COMMAND ${cli_refuse} 1 "huge.png: the image of 65535 x 65535 pixels would need about .* GB of memory; the limit is"
         sh -c "python3 \"$1/png.py\" 65535 65535 \"$1/huge.png\" && exec \"$0\" texture tiles --exemplar \"$1/huge.png\" --out \"$1/exemplar_huge\""
         "${WANGSCAPE_BIN}" "${hostile_dir}")
add_test(NAME hostile_exemplar_damaged
         COMMAND ${cli_refuse} 1 "^wangscape: error: cannot read image '.*short.png': PNG read error: Not enough image data$"
         sh -c "python3 \"$1/png.py\" 64 64 \"$1/short.png\" && exec \"$0\" texture tiles --exemplar \"$1/short.png\" --out \"$1/exemplar_short\""
         "${WANGSCAPE_BIN}" "${hostile_dir}")
# A preview that cannot be written leaves no tiles folder (it is written first).
foreach(kind IN ITEMS noise texture)
  set(exemplar "")
  if(kind STREQUAL "texture")
    set(exemplar "--exemplar meadow")
  endif()
  add_test(NAME hostile_${kind}_tiles_preview_unwritable
           COMMAND ${cli_refuse} 0 "no image format for extension '.txt'; name a .png"
           sh -c "rm -rf \"$1\" && ! \"$0\" ${kind} tiles ${exemplar} --out \"$1\" --preview 64x64 \"$1.txt\" && ! ls \"$1\""
           "${WANGSCAPE_BIN}" "${hostile_dir}/${kind}_preview_tiles")
endforeach()
set_tests_properties(hostile_exemplar_dev_zero hostile_exemplar_fifo hostile_exemplar_huge hostile_exemplar_damaged
                     hostile_noise_tiles_preview_unwritable hostile_texture_tiles_preview_unwritable
                     PROPERTIES LABELS "cli;hostile" TIMEOUT 60)

# `--out ""`: tiling exited 0 writing nothing; tiles tried to make a folder ''.
add_test(NAME hostile_tiling_empty_out COMMAND ${cli_refuse} 2 "--out: is empty; name a file or folder"
         sh -c "exec \"$0\" tiling --set cohen8 --size 4x4 --out ''" "${WANGSCAPE_BIN}")
add_test(NAME hostile_tiles_empty_out COMMAND ${cli_refuse} 2 "--out: is empty; name a file or folder"
         sh -c "exec \"$0\" noise tiles --out ''" "${WANGSCAPE_BIN}")
set_tests_properties(hostile_tiling_empty_out hostile_tiles_empty_out PROPERTIES LABELS "cli;hostile" TIMEOUT 60)

# A rebuild swaps the folders in one exchange (renameat2 RENAME_EXCHANGE), so a reader or a kill
# at any moment finds the old build or the new one: never a rename of the folder aside first.
tiny_scene("${hostile_dir}/swap.toml" EXPORTS "povray = true")
find_program(STRACE strace)
if(STRACE)
  add_test(NAME hostile_rebuild_swaps_in_one_exchange
           COMMAND ${cli_refuse} 0 "renameat2\\(AT_FDCWD, \".*/\\.swap\\.partial-[0-9]+\", AT_FDCWD, \".*/swap\", RENAME_EXCHANGE\\) = 0"
           sh -c "rm -rf \"$1/swap\" && \"$0\" --quiet build \"$1/swap.toml\" --out \"$1/swap\" && \"$2\" -f -e trace=rename,renameat,renameat2 \"$0\" --quiet build \"$1/swap.toml\" --out \"$1/swap\" 2>&1 | grep -v '\\.old-' | grep -E 'rename.*/swap\"' && [ -s \"$1/swap/scene.toml\" ] && ! ls -a \"$1\" | grep -E '^\\.swap\\.'"
           "${WANGSCAPE_BIN}" "${hostile_dir}" "${STRACE}")
  set_tests_properties(hostile_rebuild_swaps_in_one_exchange PROPERTIES LABELS "cli;hostile" TIMEOUT 60)
endif()

# Where the filesystem refuses the exchange (bindfs, FUSE: EINVAL), the rebuild falls back to
# two renames and says so.
add_test(NAME hostile_rebuild_swap_fallback
         COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/swap_fallback.sh" "${WANGSCAPE_BIN}" "${hostile_dir}/swap.toml"
                 "${hostile_dir}/swap_fallback")
set_tests_properties(hostile_rebuild_swap_fallback PROPERTIES LABELS "cli;hostile" TIMEOUT 60 SKIP_RETURN_CODE 77)

# A DEM whose CRS name is not UTF-8 (byte 0xFF): JSON gets U+FFFD, scene.pov stays UTF-8.
add_test(NAME hostile_crs_not_utf8
         COMMAND sh "${CMAKE_CURRENT_SOURCE_DIR}/crs_not_utf8.sh" "${WANGSCAPE_BIN}" "${PROJECT_SOURCE_DIR}"
                 "${hostile_dir}/crs_not_utf8")
set_tests_properties(hostile_crs_not_utf8 PROPERTIES LABELS "cli;hostile" TIMEOUT 60)

# A refused build leaves no parent folders it made (here POV-Ray refuses the folder's name, after
# the parents were made for its staging folder).
add_test(NAME hostile_build_refused_leaves_no_parents
         COMMAND ${cli_refuse} 0 "POV-Ray cannot use this path"
         sh -c "rm -rf \"$1/made\" && ! \"$0\" --quiet build \"$2\" --out \"$1/made/b/c\\\"d\" && ! ls -d \"$1/made\""
         "${WANGSCAPE_BIN}" "${hostile_dir}" "${hostile_dir}/swap.toml")
set_tests_properties(hostile_build_refused_leaves_no_parents PROPERTIES LABELS "cli;hostile" TIMEOUT 60)
