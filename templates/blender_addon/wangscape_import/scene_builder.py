# Builds a Blender scene from a Wangscape manifest (docs/blender-format.md). Arrays are read
# with numpy.fromfile and handed to Blender with foreach_set: no per-element Python loops,
# so a million instances import in about a second.

import json
import math
import os
import time

import bpy
import numpy as np
from mathutils import Vector

FORMAT_NAME = "wangscape-blender"
FORMAT_VERSION = 1
MODELS_COLLECTION = "Wangscape models"
FIELD_OBJECT = "Wangscape flowers"
NODE_GROUP = "Wangscape instancing"
RADIANS_PER_DEGREE = math.pi / 180
BLENDERGIS_KEYS = ("SRID", "crs x", "crs y", "latitude", "longitude")

DTYPES = {"float32": "<f4", "uint32": "<u4", "uint16": "<u2", "int32": "<i4"}


class ManifestError(Exception):
    """A manifest or one of its arrays is missing, malformed or of an unknown version."""


def load_manifest(path):
    try:
        with open(path, "r", encoding="utf-8") as stream:
            manifest = json.load(stream)
    except (OSError, ValueError) as error:
        raise ManifestError("cannot read Wangscape manifest '%s': %s" % (path, error))
    fmt = manifest.get("format", {})
    if fmt.get("name") != FORMAT_NAME:
        raise ManifestError("'%s' is not a Wangscape Blender manifest (format name '%s')" % (path, fmt.get("name")))
    if fmt.get("version") != FORMAT_VERSION:
        raise ManifestError(
            "'%s' has format version %s; this add-on reads version %d" % (path, fmt.get("version"), FORMAT_VERSION)
        )
    return manifest


def read_array(folder, entry):
    """The array described by a manifest entry {file, dtype, components, count}, flat."""
    path = os.path.join(folder, entry["file"])
    dtype = DTYPES.get(entry["dtype"])
    if dtype is None:
        raise ManifestError("'%s': unknown dtype '%s'" % (path, entry["dtype"]))
    expected = int(entry["count"]) * int(entry.get("components", 1))
    try:
        data = np.fromfile(path, dtype=dtype)
    except OSError as error:
        raise ManifestError("cannot read array '%s': %s" % (path, error))
    if data.size != expected:
        raise ManifestError("'%s' holds %d values; the manifest says %d" % (path, data.size, expected))
    return data


# --- version guards (Blender 3.4 .. 4.x) -------------------------------------------------


def _has_rna_property(rna_type, name):
    return name in rna_type.bl_rna.properties


def new_group_socket(group, in_out, name, socket_type):
    """Adds a node-group input/output socket: 4.0 moved them to group.interface."""
    if hasattr(group, "interface"):
        return group.interface.new_socket(name=name, in_out=in_out, socket_type=socket_type)
    sockets = group.inputs if in_out == "INPUT" else group.outputs
    return sockets.new(socket_type, name)


def enabled_output(node, name):
    """The visible output called name (3.x Named Attribute has one hidden output per type)."""
    for socket in node.outputs:
        if socket.name == name and socket.enabled:
            return socket
    return node.outputs[name]


def principled_input(node, *names):
    """The first input that exists among names (4.0 renamed several Principled inputs)."""
    for name in names:
        if name in node.inputs:
            return node.inputs[name]
    return None


# --- meshes ------------------------------------------------------------------------------


def build_mesh(name, folder, spec, materials):
    """A Blender mesh from a manifest mesh entry; materials is the manifest-wide list."""
    positions = read_array(folder, spec["positions"])
    normals = read_array(folder, spec["normals"])
    indices = read_array(folder, spec["indices"]).astype(np.int32)
    vertex_count = positions.size // 3
    triangle_count = indices.size // 3

    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(vertex_count)
    mesh.vertices.foreach_set("co", positions)
    mesh.loops.add(triangle_count * 3)
    mesh.loops.foreach_set("vertex_index", indices)
    mesh.polygons.add(triangle_count)
    mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * triangle_count, 3, dtype=np.int32))
    if _loop_total_writable():
        mesh.polygons.foreach_set("loop_total", np.full(triangle_count, 3, dtype=np.int32))
    if "material_indices" in spec and spec["material_indices"]:
        slot_of_triangle = read_array(folder, spec["material_indices"]).astype(np.int32)
        mesh.polygons.foreach_set("material_index", slot_of_triangle)
    mesh.polygons.foreach_set("use_smooth", np.ones(triangle_count, dtype=bool))
    mesh.update(calc_edges=True)

    # The exporter's normals (DEM gradients, model normals) rather than Blender's guess.
    if _has_rna_property(bpy.types.Mesh, "use_auto_smooth"):
        mesh.use_auto_smooth = True  # required for custom normals before 4.1
    mesh.normals_split_custom_set_from_vertices(normals.reshape(-1, 3))

    if spec.get("uvs"):
        # A model's own uvs (v up, as Blender's), per vertex: spread to the loops.
        uv = read_array(folder, spec["uvs"]).reshape(-1, 2)
        mesh.uv_layers.new(name="UVMap").data.foreach_set("uv", uv[indices].ravel())

    for slot in spec.get("material_slots", []):
        mesh.materials.append(materials[slot])
    return mesh


def apply_ground_texture(mesh, folder, spec):
    """The scene's baked [ground] look: one image over the ENU extent, UVs from vertex positions."""
    min_x, min_y, max_x, max_y = (float(v) for v in spec["extent"])
    co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    loops = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", loops)
    uv = np.empty((len(loops), 2), dtype=np.float32)
    uv[:, 0] = (co[loops, 0] - min_x) / (max_x - min_x)
    uv[:, 1] = (co[loops, 1] - min_y) / (max_y - min_y)  # Blender's v runs up: north at the top
    mesh.uv_layers.new(name="ground").data.foreach_set("uv", uv.ravel())

    material = bpy.data.materials.new("Wangscape ground")
    material.use_nodes = True
    tree = material.node_tree
    principled = next(node for node in tree.nodes if node.type == "BSDF_PRINCIPLED")
    principled.inputs["Roughness"].default_value = 0.9
    specular = principled_input(principled, "Specular", "Specular IOR Level")
    if specular is not None:
        specular.default_value = 0.0  # diffuse alone, as the one shading model's ground
    texture = tree.nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(os.path.join(folder, spec["file"]), check_existing=True)
    texture.extension = "EXTEND"
    tree.links.new(texture.outputs["Color"], principled.inputs["Base Color"])
    material["wangscape_name"] = "ground"
    mesh.materials.clear()
    mesh.materials.append(material)
    mesh.polygons.foreach_set("material_index", np.zeros(len(mesh.polygons), dtype=np.int32))


def _loop_total_writable():
    # Blender 3.6+ derives polygon sizes from loop_start and made loop_total read-only.
    prop = bpy.types.MeshPolygon.bl_rna.properties.get("loop_total")
    return prop is not None and not prop.is_readonly


def build_material(spec, folder):
    """Principled BSDF, mixed with a Translucent BSDF for thin parts (petals, leaves); with an
    image, its colour (which holds the base colour already) and, for a cutout, its alpha, clipped."""
    material = bpy.data.materials.new(spec["name"])
    material.use_nodes = True
    color = list(spec["base_color"]) + [1.0]
    material.diffuse_color = color
    material.roughness = float(spec.get("roughness", 0.5))
    tree = material.node_tree
    principled = next(node for node in tree.nodes if node.type == "BSDF_PRINCIPLED")
    principled.inputs["Base Color"].default_value = color
    principled.inputs["Roughness"].default_value = material.roughness
    specular = principled_input(principled, "Specular", "Specular IOR Level")
    if specular is not None:
        specular.default_value = 0.0  # diffuse alone, as the one shading model
    image = None
    if spec.get("image"):
        image = tree.nodes.new("ShaderNodeTexImage")
        image.image = bpy.data.images.load(os.path.join(folder, spec["image"]), check_existing=True)
        tree.links.new(image.outputs["Color"], principled.inputs["Base Color"])
        if spec.get("alpha_clip"):
            tree.links.new(image.outputs["Alpha"], principled.inputs["Alpha"])
            material.blend_method = "CLIP"  # EEVEE; Cycles takes the alpha as it is (0 or 1 here)
            material.alpha_threshold = 0.5
            if hasattr(material, "shadow_method"):
                material.shadow_method = "CLIP"
    translucency = float(spec.get("translucency", 0.0))
    if translucency > 0.0:
        output = next(node for node in tree.nodes if node.type == "OUTPUT_MATERIAL")
        # The front keeps all its diffuse light and the back passes `translucency` of it, as in
        # the one shading model (sun_share) and POV-Ray's back-side diffuse: added, not mixed.
        translucent = tree.nodes.new("ShaderNodeBsdfTranslucent")
        translucent.inputs["Color"].default_value = [c * translucency for c in color[:3]] + [1.0]
        if image is not None:  # the image's colour times the translucency
            scaled = tree.nodes.new("ShaderNodeMixRGB")
            scaled.blend_type = "MULTIPLY"
            scaled.inputs["Fac"].default_value = 1.0
            scaled.inputs["Color2"].default_value = [translucency] * 3 + [1.0]
            tree.links.new(image.outputs["Color"], scaled.inputs["Color1"])
            tree.links.new(scaled.outputs["Color"], translucent.inputs["Color"])
        add = tree.nodes.new("ShaderNodeAddShader")
        tree.links.new(principled.outputs["BSDF"], add.inputs[0])
        tree.links.new(translucent.outputs["BSDF"], add.inputs[1])
        tree.links.new(add.outputs["Shader"], output.inputs["Surface"])
    material["wangscape_name"] = spec["name"]
    return material


# --- instancing --------------------------------------------------------------------------


def build_models_collection(context, folder, manifest, materials):
    """One object per variant, named so Collection Info (sorted by name) keeps manifest order."""
    collection = bpy.data.collections.new(MODELS_COLLECTION)
    context.scene.collection.children.link(collection)
    for index, spec in enumerate(manifest["models"]):
        mesh = build_mesh("%s %04d %s" % ("variant", index, spec.get("name", "")), folder, spec, materials)
        obj = bpy.data.objects.new("variant %04d" % index, mesh)
        obj["wangscape_variant"] = index
        if "species" in spec:  # [[species]]: the species this model belongs to
            obj["wangscape_species"] = manifest["species"][spec["species"]]
        collection.objects.link(obj)
    # Hidden: excluded from the view layer, still instanced by Collection Info.
    layer_collection = context.view_layer.layer_collection.children.get(collection.name)
    if layer_collection is not None:
        layer_collection.exclude = True
    return collection


def build_instancing_group(collection, wind=None):
    """Geometry nodes: Instance on Points picking a child of the collection per point; with the
    manifest's wind, each instance then leans about its base (build_wind_sway)."""
    group = bpy.data.node_groups.new(NODE_GROUP, "GeometryNodeTree")
    new_group_socket(group, "INPUT", "Geometry", "NodeSocketGeometry")
    new_group_socket(group, "OUTPUT", "Geometry", "NodeSocketGeometry")
    nodes, links = group.nodes, group.links
    group_in = nodes.new("NodeGroupInput")
    group_out = nodes.new("NodeGroupOutput")
    group_in.location, group_out.location = (-600, 0), (400, 0)

    info = nodes.new("GeometryNodeCollectionInfo")
    info.location = (-300, 250)
    info.transform_space = "ORIGINAL"
    info.inputs["Collection"].default_value = collection
    info.inputs["Separate Children"].default_value = True
    info.inputs["Reset Children"].default_value = True

    def named_attribute(name, data_type, y):
        node = nodes.new("GeometryNodeInputNamedAttribute")
        node.data_type = data_type
        node.inputs["Name"].default_value = name
        node.location = (-300, y)
        return enabled_output(node, "Attribute")

    instance = nodes.new("GeometryNodeInstanceOnPoints")
    instance.location = (100, 0)
    instance.inputs["Pick Instance"].default_value = True
    links.new(group_in.outputs[0], instance.inputs["Points"])
    links.new(info.outputs[0], instance.inputs["Instance"])
    links.new(named_attribute("variant", "INT", 0), instance.inputs["Instance Index"])
    links.new(named_attribute("rotation", "FLOAT_VECTOR", -150), instance.inputs["Rotation"])
    links.new(named_attribute("scale", "FLOAT", -300), instance.inputs["Scale"])
    if wind:
        swayed = build_wind_sway(nodes, links, wind)
        links.new(instance.outputs[0], swayed.inputs["Instances"])
        links.new(swayed.outputs[0], group_out.inputs[0])
    else:
        links.new(instance.outputs[0], group_out.inputs[0])
    return group


def build_wind_sway(nodes, links, wind):
    """Rotate Instances by the wind's lean (docs/blender-format.md "wind"): at each plant's place
    (E, N) and the scene time t in seconds, east = base_east + sum of amplitude_east *
    sin(k_east E + k_north N + k_time t + phase), north likewise, in degrees; the plant turns
    about its base by Euler XYZ (-north, east, 0), in world axes."""
    position = nodes.new("GeometryNodeInputPosition")
    place = nodes.new("ShaderNodeSeparateXYZ")
    links.new(position.outputs[0], place.inputs[0])
    seconds = nodes.new("GeometryNodeInputSceneTime").outputs["Seconds"]

    def scalar(operation, a, b=0.0, c=0.0):
        node = nodes.new("ShaderNodeMath")
        node.operation = operation
        for socket, value in zip(node.inputs, (a, b, c)):
            if isinstance(value, bpy.types.NodeSocket):
                links.new(value, socket)
            else:
                socket.default_value = value
        return node.outputs[0]

    east, north = wind["base_east"], wind["base_north"]
    for wave in wind["waves"]:
        phase = scalar("MULTIPLY_ADD", place.outputs["X"], wave["k_east"], wave["phase"])
        phase = scalar("MULTIPLY_ADD", place.outputs["Y"], wave["k_north"], phase)
        phase = scalar("MULTIPLY_ADD", seconds, wave["k_time"], phase)
        wave_value = scalar("SINE", phase)
        east = scalar("MULTIPLY_ADD", wave_value, wave["amplitude_east"], east)
        north = scalar("MULTIPLY_ADD", wave_value, wave["amplitude_north"], north)
    rotation = nodes.new("ShaderNodeCombineXYZ")
    links.new(scalar("MULTIPLY", north, -RADIANS_PER_DEGREE), rotation.inputs["X"])
    links.new(scalar("MULTIPLY", east, RADIANS_PER_DEGREE), rotation.inputs["Y"])
    sway = nodes.new("GeometryNodeRotateInstances")
    sway.location = (300, 0)
    links.new(rotation.outputs[0], sway.inputs["Rotation"])
    links.new(position.outputs[0], sway.inputs["Pivot Point"])
    sway.inputs["Local Space"].default_value = False
    return sway


def build_field(context, folder, manifest, collection):
    """A vertex-only mesh (one point per flower) whose modifier instances the variants."""
    spec = manifest["instances"]
    count = int(spec["count"])
    mesh = bpy.data.meshes.new(FIELD_OBJECT)
    if count > 0:
        positions = np.empty((count, 3), dtype=np.float32)
        positions[:, 0] = read_array(folder, spec["x"])
        positions[:, 1] = read_array(folder, spec["y"])
        positions[:, 2] = read_array(folder, spec["z"])
        mesh.vertices.add(count)
        mesh.vertices.foreach_set("co", positions.ravel())
        del positions
        variant = read_array(folder, spec["variant"]).astype(np.int32)
        if variant.size and int(variant.max()) >= len(manifest["models"]):
            raise ManifestError("instance variant %d but only %d models" % (int(variant.max()), len(manifest["models"])))
        mesh.attributes.new("variant", "INT", "POINT").data.foreach_set("value", variant)
        if "species" in manifest:
            # [[species]]: each flower's species (an index into manifest["species"]) from its model.
            model_species = np.array([m.get("species", -1) for m in manifest["models"]], dtype=np.int32)
            mesh.attributes.new("species", "INT", "POINT").data.foreach_set("value", model_species[variant])
        del variant
        rotation = np.zeros((count, 3), dtype=np.float32)
        rotation[:, 2] = read_array(folder, spec["yaw"])  # yaw: counter-clockwise about +z
        mesh.attributes.new("rotation", "FLOAT_VECTOR", "POINT").data.foreach_set("vector", rotation.ravel())
        del rotation
        scale = read_array(folder, spec["scale"])
        mesh.attributes.new("scale", "FLOAT", "POINT").data.foreach_set("value", scale)
    mesh.update()
    obj = bpy.data.objects.new(FIELD_OBJECT, mesh)
    context.scene.collection.objects.link(obj)
    modifier = obj.modifiers.new("Wangscape instancing", "NODES")
    modifier.node_group = build_instancing_group(collection, manifest.get("wind"))
    obj["wangscape_instance_count"] = count
    return obj


# --- camera, sun, sky, render settings ---------------------------------------------------


def build_camera(context, spec, scene_extent):
    data = bpy.data.cameras.new("Wangscape camera")
    data.sensor_fit = "HORIZONTAL"
    data.angle = math.radians(float(spec["fov_degrees"]))
    data.clip_start = 0.05
    data.clip_end = max(1000.0, 4.0 * scene_extent)
    obj = bpy.data.objects.new("Wangscape camera", data)
    position = Vector(spec["position"])
    obj.location = position
    forward = Vector(spec["target"]) - position
    if forward.length > 0.0:
        obj.rotation_mode = "QUATERNION"
        obj.rotation_quaternion = forward.to_track_quat("-Z", "Y")  # cameras look down -z
    context.scene.collection.objects.link(obj)
    context.scene.camera = obj
    return obj


def build_sun_and_sky(context, spec, light=None):
    """A sun lamp shining along -direction, and the sky. With the manifest's light (the one
    shading model's, docs/blender-format.md): the lamp's color and strength, and a world that
    shows the sky's gradient to the camera and lights the scene with the open sky's uniform
    color. Without it (older manifests): a Nishita sky whose sun sits at the same place."""
    data = bpy.data.lights.new("Wangscape sun", "SUN")
    data.energy = 3.0 * float(spec.get("strength", 1.0))  # W/m^2: bright daylight under Filmic
    data.angle = math.radians(0.53)  # the sun's apparent diameter
    if light:
        # A sun of strength E lights a white diffuse surface facing it to E / pi (measured in
        # Cycles 3.4), lit() to sun_color: strength pi times the brightest channel, color the rest.
        sun_color = [float(c) for c in light["sun_color"]]
        brightest = max(sun_color + [1e-6])
        data.energy = math.pi * brightest
        data.color = [c / brightest for c in sun_color]
    obj = bpy.data.objects.new("Wangscape sun", data)
    obj.rotation_mode = "QUATERNION"
    obj.rotation_quaternion = Vector(spec["direction"]).to_track_quat("Z", "Y")  # lamps shine down -z
    context.scene.collection.objects.link(obj)

    world = bpy.data.worlds.new("Wangscape sky")
    world.use_nodes = True
    tree = world.node_tree
    background = next(node for node in tree.nodes if node.type == "BACKGROUND")
    if light:
        build_gradient_sky(tree, background, light)
        context.scene.world = world
        return obj
    sky = tree.nodes.new("ShaderNodeTexSky")
    sky.sky_type = "NISHITA"
    sky.sun_disc = False  # the lamp is the sun; a disc too would light the scene twice
    sky.sun_elevation = math.radians(float(spec["elevation_degrees"]))
    sky.sun_rotation = math.radians(float(spec["azimuth_degrees"]))  # both clockwise from north
    background.inputs["Strength"].default_value = 0.3
    tree.links.new(sky.outputs["Color"], background.inputs["Color"])
    context.scene.world = world
    return obj


def build_gradient_sky(tree, background, light):
    """sky_radiance() of scene/shading_light.h for camera rays (horizon to zenith by the square
    root of the ray's up component); the uniform sky_color for the light on surfaces, whose
    irradiance under the open sky is then sky_color, as in lit()."""
    direction = tree.nodes.new("ShaderNodeTexCoord")  # Generated, in a world: the ray's direction
    split = tree.nodes.new("ShaderNodeSeparateXYZ")
    tree.links.new(direction.outputs["Generated"], split.inputs["Vector"])
    up = tree.nodes.new("ShaderNodeMath")
    up.operation = "MAXIMUM"
    up.inputs[1].default_value = 0.0
    tree.links.new(split.outputs["Z"], up.inputs[0])
    root = tree.nodes.new("ShaderNodeMath")
    root.operation = "SQRT"
    tree.links.new(up.outputs["Value"], root.inputs[0])
    gradient = tree.nodes.new("ShaderNodeMixRGB")
    gradient.blend_type = "MIX"
    gradient.inputs["Color1"].default_value = [float(c) for c in light["sky_horizon"]] + [1.0]
    gradient.inputs["Color2"].default_value = [float(c) for c in light["sky_zenith"]] + [1.0]
    tree.links.new(root.outputs["Value"], gradient.inputs["Fac"])
    path = tree.nodes.new("ShaderNodeLightPath")
    seen = tree.nodes.new("ShaderNodeMixRGB")
    seen.blend_type = "MIX"
    seen.inputs["Color1"].default_value = [float(c) for c in light["sky_color"]] + [1.0]
    tree.links.new(path.outputs["Is Camera Ray"], seen.inputs["Fac"])
    tree.links.new(gradient.outputs["Color"], seen.inputs["Color2"])
    tree.links.new(seen.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = 1.0


def set_linear_exposure(scene, exposure):
    """The one shading model's output: linear RGB times the exposure, sRGB-encoded, no tone curve."""
    settings = scene.view_settings
    settings.view_transform = "Standard"
    settings.look = "None"
    settings.exposure = math.log2(max(float(exposure), 1e-6))
    settings.gamma = 1.0


def set_view_transform(scene):
    """Filmic with a high-contrast look: closest to POV-Ray's sRGB output for a sunlit field."""
    settings = scene.view_settings
    try:
        settings.view_transform = "Filmic"
    except TypeError:
        return  # a build without Filmic: keep its default
    for look in ("High Contrast", "Filmic - High Contrast"):  # the look's name changed in 4.0
        try:
            settings.look = look
            return
        except TypeError:
            continue


def apply_render_settings(scene, spec, light=None):
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = int(spec.get("samples", 16))
    # A ray goes on through leaf cards' cut-out holes as far as it needs, as through the Embree
    # reference's alpha filter and POV-Ray's transmit. At Cycles' default of 8 a ray stopped black
    # after 8 holes (a shadow ray counted as blocked), and the middle distance of a dense field of
    # cards turned dark (templates/scenes/card-plants.toml: CIEDE2000 6.5 from POV-Ray, now 4.7).
    scene.cycles.transparent_max_bounces = 1024  # the most Cycles takes
    scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
    if hasattr(scene.cycles, "use_preview_denoising"):
        scene.cycles.use_preview_denoising = False
    if light:
        # Direct light only (the sun and the sky, shadowed), as the one shading model: no light
        # bounced off the ground or the plants.
        scene.cycles.max_bounces = 0
        set_linear_exposure(scene, light.get("exposure", 1.0))
    else:
        set_view_transform(scene)
    scene.render.resolution_x = int(spec["width"])
    scene.render.resolution_y = int(spec["height"])
    scene.render.resolution_percentage = 100
    threads = int(spec.get("threads", 0))
    scene.render.threads_mode = "FIXED" if threads > 0 else "AUTO"
    if threads > 0:
        scene.render.threads = threads


def apply_georeference(scene, manifest):
    """BlenderGIS keys on the scene (so its tools line up), plus every original pair."""
    for key, value in manifest.get("blendergis", {}).items():
        if key in BLENDERGIS_KEYS:
            scene[key] = value
    pairs = manifest.get("georeference", {})
    if pairs:
        scene["wangscape_georeference"] = {str(key): str(value) for key, value in pairs.items()}


# --- entry point -------------------------------------------------------------------------


def _extent(manifest):
    corners = []
    for section in [manifest.get("terrain")] + [manifest.get("instances")]:
        if section and section.get("bounds"):
            corners += [Vector(section["bounds"]["min"]), Vector(section["bounds"]["max"])]
    if not corners:
        return 0.0
    low = Vector([min(c[i] for c in corners) for i in range(3)])
    high = Vector([max(c[i] for c in corners) for i in range(3)])
    return (high - low).length


def import_manifest(context, path, set_render_settings=True, set_world=True):
    """Builds the scene described by the manifest at path; returns a small summary."""
    start = time.perf_counter()
    manifest = load_manifest(path)
    folder = os.path.dirname(os.path.abspath(path))
    scene = context.scene

    materials = [build_material(spec, folder) for spec in manifest["materials"]]
    terrain_spec = manifest.get("terrain")
    if terrain_spec:
        terrain_mesh = build_mesh("Wangscape terrain", folder, terrain_spec, materials)
        if manifest.get("ground_texture"):
            apply_ground_texture(terrain_mesh, folder, manifest["ground_texture"])
        terrain = bpy.data.objects.new("Wangscape terrain", terrain_mesh)
        scene.collection.objects.link(terrain)
    collection = build_models_collection(context, folder, manifest, materials)
    build_field(context, folder, manifest, collection)
    if manifest.get("wind"):
        # The wind's time is the scene time: frame 0 is its time 0, as a still's.
        scene.frame_start = 0
        scene.frame_current = 0
    build_camera(context, manifest["camera"], _extent(manifest))
    if set_world:
        build_sun_and_sky(context, manifest["sun"], manifest.get("light"))
    if set_render_settings:
        apply_render_settings(scene, manifest["render"], manifest.get("light"))
    apply_georeference(scene, manifest)
    scene["wangscape_manifest"] = os.path.abspath(path)
    return {
        "instances": int(manifest["instances"]["count"]),
        "variants": len(manifest["models"]),
        "seconds": time.perf_counter() - start,
    }
