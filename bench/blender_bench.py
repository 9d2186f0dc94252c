# Timing script for bench/blender_bench.cpp, run inside Blender:
#   blender -b --factory-startup --python blender_bench.py -- addon ADDON_ZIP MANIFEST
#   blender -b --factory-startup --python blender_bench.py -- gltf FILE.glb
#   blender -b --factory-startup --python blender_bench.py -- render ADDON_ZIP MANIFEST WIDTH HEIGHT
# Prints "bench: <name> <seconds>" lines that the C++ side parses.
import sys
import time

import bpy

args = sys.argv[sys.argv.index("--") + 1 :]
mode = args[0]
for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.cameras, bpy.data.lights):
    for item in list(collection):
        collection.remove(item)


def evaluated_instances():
    depsgraph = bpy.context.evaluated_depsgraph_get()
    return depsgraph, sum(1 for i in depsgraph.object_instances if i.is_instance)


if mode in ("addon", "render"):
    sys.path.insert(0, args[1])
    import wangscape_import

    wangscape_import.register()
    start = time.perf_counter()
    assert bpy.ops.import_scene.wangscape(filepath=args[2]) == {"FINISHED"}
    bpy.context.view_layer.update()  # geometry nodes evaluated: the instances exist
    print("bench: import %.6f" % (time.perf_counter() - start))
    if mode == "addon":
        start = time.perf_counter()
        _, count = evaluated_instances()
        print("bench: count_instances %.6f" % (time.perf_counter() - start))
        print("bench: instances %d" % count)
    else:
        scene = bpy.context.scene
        scene.render.resolution_x, scene.render.resolution_y = int(args[3]), int(args[4])
        scene.render.filepath = "/dev/null"
        start = time.perf_counter()
        bpy.ops.render.render(write_still=False)
        print("bench: render %.6f" % (time.perf_counter() - start))
        print("bench: samples %d" % scene.cycles.samples)
elif mode == "gltf":
    start = time.perf_counter()
    # Blender 3.4's importer crashes on numpy 1.24 unless shading is SMOOTH or FLAT.
    assert bpy.ops.import_scene.gltf(filepath=args[1], import_shading="SMOOTH") == {"FINISHED"}
    bpy.context.view_layer.update()
    print("bench: import %.6f" % (time.perf_counter() - start))
    print("bench: objects %d" % len(bpy.data.objects))
else:
    raise SystemExit("unknown mode " + mode)
