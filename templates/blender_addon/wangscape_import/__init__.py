# Wangscape scene importer for Blender: File > Import > Wangscape scene (manifest).
#
# Reads the folder `wangscape build` writes with `[exports] blender = true` (manifest.json +
# little-endian arrays, see docs/blender-format.md) and builds the terrain, one object per
# model variant in a hidden collection, and the flowers as geometry-nodes instances (never
# realized), with materials, sun, Nishita sky, camera, render settings and the
# georeference as BlenderGIS scene properties. Works on Blender 3.4 and guards 4.x changes.

bl_info = {
    "name": "Wangscape scene importer",
    "author": "Wangscape",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > Wangscape scene (manifest)",
    "description": "Terrain and sunflower fields from Wangscape, instanced with geometry nodes",
    "category": "Import-Export",
}

import bpy
from bpy.props import BoolProperty, StringProperty
from bpy_extras.io_utils import ImportHelper

from . import scene_builder


class IMPORT_SCENE_OT_wangscape(bpy.types.Operator, ImportHelper):
    """Import a Wangscape scene (manifest.json and its binary arrays)"""

    bl_idname = "import_scene.wangscape"
    bl_label = "Import Wangscape scene"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})
    set_render_settings: BoolProperty(
        name="Render settings",
        description="Use the manifest's resolution, samples and Cycles on the CPU",
        default=True,
    )
    set_world: BoolProperty(
        name="Sun and sky",
        description="Replace the world with a Nishita sky and add a sun lamp matching the scene's sun",
        default=True,
    )

    def execute(self, context):
        try:
            summary = scene_builder.import_manifest(
                context,
                self.filepath,
                set_render_settings=self.set_render_settings,
                set_world=self.set_world,
            )
        except scene_builder.ManifestError as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        self.report(
            {"INFO"},
            "Wangscape: %d instances of %d variants in %.2f s"
            % (summary["instances"], summary["variants"], summary["seconds"]),
        )
        return {"FINISHED"}


def menu_func_import(self, context):
    self.layout.operator(IMPORT_SCENE_OT_wangscape.bl_idname, text="Wangscape scene (manifest)")


def register():
    bpy.utils.register_class(IMPORT_SCENE_OT_wangscape)
    bpy.types.TOPBAR_MT_file_import.append(menu_func_import)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(menu_func_import)
    bpy.utils.unregister_class(IMPORT_SCENE_OT_wangscape)


if __name__ == "__main__":
    register()
