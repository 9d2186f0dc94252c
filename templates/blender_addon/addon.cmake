# The Blender add-on (templates/blender_addon/wangscape_import): embedded into
# wangscape_templates (blender_addon_files()); exporters/zip_writer.h packs it as the
# wangscape_import.zip every Blender export carries (Edit > Preferences > Add-ons > Install).
set(addon_dir "${CMAKE_CURRENT_SOURCE_DIR}/blender_addon")
set(addon_files wangscape_import/__init__.py wangscape_import/scene_builder.py)
list(TRANSFORM addon_files PREPEND "${addon_dir}/" OUTPUT_VARIABLE addon_paths)
set(addon_cpp "${CMAKE_CURRENT_BINARY_DIR}/blender_addon_files.cpp")
string(REPLACE ";" "|" addon_files_arg "${addon_files}")  # a list would split the argument
add_custom_command(OUTPUT "${addon_cpp}"
  COMMAND ${CMAKE_COMMAND} -DADDON_DIR=${addon_dir} -DOUTPUT=${addon_cpp} "-DFILES=${addon_files_arg}"
          -P "${addon_dir}/embed_addon.cmake"
  DEPENDS ${addon_paths} "${addon_dir}/embed_addon.cmake"
  COMMENT "Embedding the Blender add-on" VERBATIM)
target_sources(wangscape_templates PRIVATE "${addon_cpp}")

