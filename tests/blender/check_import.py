# Runs inside the real Blender (blender -b --factory-startup --python-exit-code 1 --python
# check_import.py -- ADDON_ZIP MANIFEST [BLENDERGIS_KEY_COUNT]): installs nothing, imports the add-on from its zip,
# imports the manifest through the File > Import operator, and checks the result against the
# manifest and its arrays. Any failed check raises, so Blender exits with status 1.

import json
import math
import os
import sys
from collections import Counter

import bpy
import numpy as np
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1 :]
addon_zip, manifest_path = args[0], args[1]
expected_blendergis_keys = int(args[2]) if len(args) > 2 else None  # optional: how many the scene must carry
sys.path.insert(0, addon_zip)
import wangscape_import  # noqa: E402  (from the zip)

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("wangscape-check: FAIL:", message)


def close(a, b, tolerance):
    return all(abs(float(x) - float(y)) <= tolerance for x, y in zip(a, b))


# --- the add-on installs like a stock add-on: bl_info, operator, menu entry --------------
check(tuple(wangscape_import.bl_info["blender"]) <= (3, 4, 0), "bl_info must accept Blender 3.4")
wangscape_import.register()
check(hasattr(bpy.ops.import_scene, "wangscape"), "operator import_scene.wangscape registered")
menu_entries = [f.__name__ for f in bpy.types.TOPBAR_MT_file_import._dyn_ui_initialize()]
check("menu_func_import" in menu_entries, "File > Import menu entry registered")

for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.cameras, bpy.data.lights):
    for item in list(collection):
        collection.remove(item)

result = bpy.ops.import_scene.wangscape(filepath=manifest_path)
check(result == {"FINISHED"}, "import finished (%s)" % result)

with open(manifest_path) as stream:
    manifest = json.load(stream)
folder = os.path.dirname(manifest_path)
scene = bpy.context.scene
spec = manifest["instances"]


def array(entry):
    return np.fromfile(os.path.join(folder, entry["file"]), dtype={"float32": "<f4", "uint16": "<u2"}[entry["dtype"]])


# --- instances: evaluated count, per variant, and every (x, y, z, yaw, scale, variant) -----
field = bpy.data.objects["Wangscape flowers"]
depsgraph = bpy.context.evaluated_depsgraph_get()
variant_of_object = {obj.name: obj["wangscape_variant"] for obj in bpy.data.collections["Wangscape models"].objects}
seen = []
for instance in depsgraph.object_instances:
    if not instance.is_instance or instance.parent is None or instance.parent.original != field:
        continue
    matrix = instance.matrix_world
    scale = matrix.col[0].xyz.length
    yaw = math.atan2(matrix[1][0], matrix[0][0])
    t = matrix.translation
    seen.append((t.x, t.y, t.z, yaw, scale, variant_of_object[instance.object.original.name]))
check(len(seen) == spec["count"], "evaluated instances %d == manifest %d" % (len(seen), spec["count"]))
per_variant = Counter(v[5] for v in seen)
check(
    [per_variant.get(i, 0) for i in range(len(manifest["models"]))] == spec["per_variant"],
    "per-variant counts %s == manifest %s" % (dict(per_variant), spec["per_variant"]),
)
if seen:
    got = np.array(seen, dtype=np.float64)
    expected = np.stack(
        [array(spec[k]).astype(np.float64) for k in ("x", "y", "z", "yaw", "scale", "variant")], axis=1
    )
    expected[:, 3] = np.arctan2(np.sin(expected[:, 3]), np.cos(expected[:, 3]))  # yaw in (-pi, pi]
    order_got = np.lexsort((got[:, 1], got[:, 0]))
    order_expected = np.lexsort((expected[:, 1], expected[:, 0]))
    diff = np.abs(got[order_got] - expected[order_expected])
    diff[:, 3] = np.minimum(diff[:, 3], 2 * math.pi - diff[:, 3])
    check(diff[:, :3].max() < 1e-3, "instance positions match the arrays (max error %g m)" % diff[:, :3].max())
    check(diff[:, 3].max() < 1e-3, "instance yaw matches (max error %g rad)" % diff[:, 3].max())
    check(diff[:, 4].max() < 1e-4, "instance scale matches (max error %g)" % diff[:, 4].max())
    check(diff[:, 5].max() == 0, "each instance shows its own variant")
    low, high = got[:, :3].min(axis=0), got[:, :3].max(axis=0)
    check(close(low, spec["bounds"]["min"], 1e-3) and close(high, spec["bounds"]["max"], 1e-3), "instance bounds")

# --- [[species]]: every flower's species attribute is its model's species, every species shows --
if "species" in manifest:
    names = manifest["species"]
    attribute = field.data.attributes.get("species")
    check(attribute is not None, "the field carries a species attribute")
    if attribute is not None and spec["count"]:
        species = np.empty(len(attribute.data), dtype=np.int32)
        attribute.data.foreach_get("value", species)
        model_species = np.array([m["species"] for m in manifest["models"]])
        check(
            np.array_equal(species, model_species[array(spec["variant"]).astype(np.int64)]),
            "each flower's species is its model's",
        )
        per_species = Counter(names[s] for s in species)
        check(all(per_species[name] > 0 for name in names), "every species has flowers: %s" % dict(per_species))
    for obj in bpy.data.collections["Wangscape models"].objects:
        expected = names[manifest["models"][obj["wangscape_variant"]]["species"]]
        check(obj.get("wangscape_species") == expected, "%s belongs to species %s" % (obj.name, expected))

# Instances stay instances: nothing realizes them.
group = field.modifiers["Wangscape instancing"].node_group
check(
    not any(node.bl_idname == "GeometryNodeRealizeInstances" for node in group.nodes), "no Realize Instances node"
)
evaluated_field = field.evaluated_get(depsgraph)
check(len(evaluated_field.data.vertices) == 0, "the field's own evaluated mesh holds no realized geometry")
models_layer = bpy.context.view_layer.layer_collection.children["Wangscape models"]
check(models_layer.exclude, "the models collection is hidden (excluded from the view layer)")


# --- bounding boxes: terrain and every variant ---------------------------------------------
def bounds_of(obj):
    corners = np.array([obj.matrix_world @ Vector(c) for c in obj.bound_box])
    return corners.min(axis=0), corners.max(axis=0)


terrain = bpy.data.objects["Wangscape terrain"]
low, high = bounds_of(terrain)
bounds = manifest["terrain"]["bounds"]
check(close(low, bounds["min"], 1e-4) and close(high, bounds["max"], 1e-4), "terrain bounds %s %s" % (low, high))
check(len(terrain.data.polygons) == manifest["terrain"]["triangle_count"], "terrain triangle count")
# The baked [ground] look: the terrain's one material shows ground.png through its UVs.
if manifest.get("ground_texture"):
    images = [n.image for m in terrain.data.materials for n in m.node_tree.nodes if n.type == "TEX_IMAGE"]
    check(len(images) == 1 and images[0].size[0] > 0, "terrain ground texture %s" % images)
    check("ground" in terrain.data.uv_layers, "terrain ground UVs")
for index, model in enumerate(manifest["models"]):
    obj = bpy.data.objects["variant %04d" % index]
    low, high = bounds_of(obj)
    check(
        close(low, model["bounds"]["min"], 1e-5) and close(high, model["bounds"]["max"], 1e-5),
        "variant %d bounds" % index,
    )
    slots = [manifest["materials"][s]["name"] for s in model["material_slots"]]
    check([m["wangscape_name"] for m in obj.data.materials] == slots, "variant %d material slots %s" % (index, slots))
    check(len(obj.data.polygons) == model["triangle_count"], "variant %d triangle count" % index)

for spec_material in manifest["materials"]:
    material = next(m for m in bpy.data.materials if m.get("wangscape_name") == spec_material["name"])
    principled = next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    check(
        close(principled.inputs["Base Color"].default_value[:3], spec_material["base_color"], 1e-6),
        "material %s base color" % spec_material["name"],
    )

# --- georeference (BlenderGIS keys), camera, sun, sky, render settings ---------------------
for key, value in manifest["blendergis"].items():
    check(key in scene.keys(), "scene property '%s' present" % key)
    check(scene.get(key) == value, "scene['%s'] == %r (got %r)" % (key, value, scene.get(key)))
if expected_blendergis_keys is not None:
    check(
        len(manifest["blendergis"]) == expected_blendergis_keys,
        "%d BlenderGIS keys, expected %d" % (len(manifest["blendergis"]), expected_blendergis_keys),
    )
check("wangscape_georeference" in scene.keys(), "all georeference pairs kept")

camera = scene.camera
check(camera is not None and close(camera.location, manifest["camera"]["position"], 1e-4), "camera position")
forward = camera.matrix_world.to_3x3() @ Vector((0, 0, -1))
target = Vector(manifest["camera"]["target"]) - camera.location
check(forward.angle(target) < 1e-3, "camera looks at the target")
check(abs(math.degrees(camera.data.angle) - manifest["camera"]["fov_degrees"]) < 1e-3, "camera field of view")

sun = bpy.data.objects["Wangscape sun"]
towards_sun = sun.matrix_world.to_3x3() @ Vector((0, 0, 1))
check(close(towards_sun, manifest["sun"]["direction"], 1e-4), "sun lamp points from the sun's direction")
azimuth, elevation = (math.radians(manifest["sun"][k]) for k in ("azimuth_degrees", "elevation_degrees"))
compass = (math.sin(azimuth) * math.cos(elevation), math.cos(azimuth) * math.cos(elevation), math.sin(elevation))
check(close(towards_sun, compass, 1e-4), "sun lamp at the compass azimuth/elevation")
# The one shading model's light: the lamp brings sun_color, the world shows the sky's gradient
# and lights with sky_color, no tone curve.
light = manifest["light"]
check(close(sun.data.color * (sun.data.energy / math.pi), light["sun_color"], 1e-4), "sun lamp color and strength")
mixes = [n for n in scene.world.node_tree.nodes if n.type == "MIX_RGB"]
check(any(close(n.inputs["Color1"].default_value[:3], light["sky_horizon"], 1e-4) and
          close(n.inputs["Color2"].default_value[:3], light["sky_zenith"], 1e-4) for n in mixes), "sky gradient")
check(any(close(n.inputs["Color1"].default_value[:3], light["sky_color"], 1e-4) for n in mixes), "sky light")
check(scene.view_settings.view_transform == "Standard", "no tone curve (Standard view transform)")
check(abs(2 ** scene.view_settings.exposure - light["exposure"]) < 1e-4, "exposure")

check(scene.render.engine == "CYCLES" and scene.cycles.device == "CPU", "Cycles on the CPU")
check(not scene.cycles.use_denoising, "denoising off (no OIDN in Debian's Blender)")
check(scene.render.resolution_x == manifest["render"]["width"], "render width")
check(scene.cycles.samples == manifest["render"]["samples"], "render samples")

if failures:
    raise SystemExit("wangscape-check: %d check(s) failed" % len(failures))
print(
    "wangscape-check: OK: %d instances, %d variants%s"
    % (len(seen), len(manifest["models"]), ", %d species" % len(manifest["species"]) if "species" in manifest else "")
)
