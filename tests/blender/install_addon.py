# Runs inside the real Blender with BLENDER_USER_SCRIPTS pointing at an empty folder:
#   blender -b --factory-startup --python-exit-code 1 --python install_addon.py -- ADDON_ZIP
# Installs the zip the way Edit > Preferences > Add-ons > Install does, enables it, and checks
# that File > Import offers "Wangscape scene (manifest)".
import sys

import addon_utils
import bpy

addon_zip = sys.argv[sys.argv.index("--") + 1]
result = bpy.ops.preferences.addon_install(filepath=addon_zip, overwrite=True)
assert result == {"FINISHED"}, "addon_install: %s" % result
result = bpy.ops.preferences.addon_enable(module="wangscape_import")
assert result == {"FINISHED"}, "addon_enable: %s" % result
loaded_default, loaded_state = addon_utils.check("wangscape_import")
assert loaded_state, "wangscape_import is not enabled after installing %s" % addon_zip
assert hasattr(bpy.ops.import_scene, "wangscape"), "operator import_scene.wangscape missing"
draw_functions = bpy.types.TOPBAR_MT_file_import._dyn_ui_initialize()
assert any(f.__module__.startswith("wangscape_import") for f in draw_functions), "no File > Import entry"
module = sys.modules["wangscape_import"]
print("wangscape-install: OK: %s %s from %s" % (module.bl_info["name"], module.bl_info["version"], module.__file__))
