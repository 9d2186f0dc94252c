"""Writes Wangscape's own test models beside this script (run it again after a change):
tulip.obj + tulip.mtl: a green stem and a red head, colours by MTL Kd only (issue 38's tulip);
leaf_card.gltf + leaf_card.bin + leaf_card.png: a vertical 1 m card, y up (glTF), whose image
holds an opaque left half (red top quarter, orange below) and a transparent blue right half,
with alphaMode MASK: the blue must never show, the red must be at the top;
tulip_textured.obj + .mtl + tulip_head.png: a round tulip whose head's colour comes from an image
(map_Kd, Kd white: red above, orange below), its stem green by Kd;
leaf_cross.glb: three cards crossed at 60 degrees in one self-contained GLB (y up, its image held
inside), alphaMode MASK: red tops, orange below, every other column of the image transparent blue,
so that a ray through the field passes many holes;
tulips/ and tulip_bunch.obj: four round tulips, as a folder of variants and as four objects."""
import json
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "templates", "models"))
from make_card_plants import glb_bytes, png_rgba  # noqa: E402  (one PNG and GLB writer for the example and test models)


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# The tulip, z up, meters: a thin stem to 0.5 m, an octahedron head 0.1 m across above it.
write("tulip.mtl", "# Wangscape test model: the stem green, the head red (Kd only)\n"
      "newmtl stem\nKd 0.10 0.60 0.10\n\nnewmtl head\nKd 0.80 0.05 0.05\n")
write("tulip.obj", """# Wangscape test model: a tulip whose MTL makes the stem green and the head red
mtllib tulip.mtl
o tulip
v 0 0 0
v 0.02 0 0
v 0 0.02 0
v 0 0 0.5
v 0.1 0 0.5
v -0.1 0 0.5
v 0 0.1 0.5
v 0 -0.1 0.5
v 0 0 0.62
v 0 0 0.42
usemtl stem
f 1 2 4
f 1 4 3
usemtl head
f 5 7 9
f 7 6 9
f 6 8 9
f 8 5 9
f 7 5 10
f 6 7 10
f 8 6 10
f 5 8 10
""")

# The leaf card's image: 16 x 16; left half opaque, right half transparent blue.
RED, ORANGE, CLEAR_BLUE = (200, 30, 30, 255), (230, 120, 20, 255), (20, 40, 230, 0)
write("leaf_card.png", png_rgba(16, 16, lambda x, y: CLEAR_BLUE if x >= 8 else (RED if y < 4 else ORANGE)))

# Two triangles, x -0.5..0.5, y 0..1, facing +z; glTF's v runs down the image.
positions = [(-0.5, 0, 0), (0.5, 0, 0), (0.5, 1, 0), (-0.5, 1, 0)]
normals = [(0, 0, 1)] * 4
uvs = [(0, 1), (1, 1), (1, 0), (0, 0)]
indices = [0, 1, 2, 0, 2, 3]
blob = (b"".join(struct.pack("<3f", *p) for p in positions) + b"".join(struct.pack("<3f", *n) for n in normals) +
        b"".join(struct.pack("<2f", *t) for t in uvs) + b"".join(struct.pack("<H", i) for i in indices))
write("leaf_card.bin", blob)
gltf = {
    "asset": {"version": "2.0", "generator": "Wangscape tests/data/models/make_own_models.py"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "leaf_card"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                "material": 0}]}],
    "materials": [{"name": "leaf", "doubleSided": True, "alphaMode": "MASK", "alphaCutoff": 0.5,
                   "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0,
                                            "roughnessFactor": 0.8}}],
    "textures": [{"source": 0, "sampler": 0}], "samplers": [{"magFilter": 9728, "minFilter": 9728}],
    "images": [{"uri": "leaf_card.png"}],
    "buffers": [{"uri": "leaf_card.bin", "byteLength": len(blob)}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, 0, 0], "max": [0.5, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
}
write("leaf_card.gltf", json.dumps(gltf, indent=1) + "\n")


# Round tulips (issue 38, variants and stand-ins), z up, meters, with texture coordinates: an
# 8-sided stem and a UV-sphere head of 20 x 14 quads (on the order of 600 triangles, more than
# the camera-aware proxies' 400, so their stand-ins are simplified). tulips/tulip_1..4.obj are
# four variants of a folder (stem heights, head sizes differ); tulip_bunch.obj holds four
# objects, one variant each with mesh_objects = "variants".
def round_tulip(first_vertex, height, head_radius, offset_x=0.0, segments=20, rings=14):
    """OBJ lines (v, vt, f with usemtl) of one round tulip; vertex and uv numbers from first_vertex."""
    import math
    lines, faces = [], []
    stem = [(0.012 * math.cos(2 * math.pi * k / 8) + offset_x, 0.012 * math.sin(2 * math.pi * k / 8), z)
            for z in (0.0, height) for k in range(8)]
    uvs = [(k / 8, z / height) for z in (0.0, height) for k in range(8)]
    for k in range(8):
        a, b = k, (k + 1) % 8
        faces.append(("stem", (a, b, b + 8)))
        faces.append(("stem", (a, b + 8, a + 8)))
    centre = height + head_radius * 0.8
    head_first = len(stem)
    for r in range(rings + 1):
        polar = math.pi * r / rings
        for s in range(segments + 1):
            azimuth = 2 * math.pi * s / segments
            stem.append((offset_x + head_radius * math.sin(polar) * math.cos(azimuth),
                         head_radius * math.sin(polar) * math.sin(azimuth), centre + head_radius * math.cos(polar)))
            uvs.append((s / segments, 1 - r / rings))
    for r in range(rings):
        for s in range(segments):
            a = head_first + r * (segments + 1) + s
            b, c, d = a + 1, a + segments + 1, a + segments + 2
            faces.append(("head", (a, c, d)))
            faces.append(("head", (a, d, b)))
    lines += ["v %.5f %.5f %.5f" % p for p in stem]
    lines += ["vt %.5f %.5f" % t for t in uvs]
    material = None
    for name, corners in faces:
        if name != material:
            lines.append("usemtl " + name)
            material = name
        lines.append("f " + " ".join("%d/%d" % (first_vertex + i, first_vertex + i) for i in corners))
    return lines, len(stem)


TULIP_SHAPES = [(0.45, 0.07), (0.5, 0.08), (0.55, 0.09), (0.6, 0.1)]  # (stem height, head radius), meters
os.makedirs(os.path.join(HERE, "tulips"), exist_ok=True)
write("tulips/tulips.mtl", "# Wangscape test model: the stem green, the head red (Kd only)\n"
      "newmtl stem\nKd 0.10 0.60 0.10\n\nnewmtl head\nKd 0.80 0.05 0.05\n")
for number, (height, radius) in enumerate(TULIP_SHAPES, start=1):
    body, _ = round_tulip(1, height, radius)
    write("tulips/tulip_%d.obj" % number, "\n".join(
        ["# Wangscape test model: round tulip variant %d (make_own_models.py)" % number, "mtllib tulips.mtl",
         "o tulip_%d" % number] + body) + "\n")
bunch, first = ["# Wangscape test model: four round tulips as four objects (make_own_models.py)",
                "mtllib tulips/tulips.mtl"], 1
for number, (height, radius) in enumerate(TULIP_SHAPES, start=1):
    body, count = round_tulip(first, height, radius, offset_x=0.3 * (number - 1))
    bunch += ["o tulip_%d" % number] + body
    first += count
write("tulip_bunch.obj", "\n".join(bunch) + "\n")

# A textured OBJ + MTL (issue 38's textured model): the round tulip, 0.5 m, its head 0.12 m in
# radius, whose colour is the image's (map_Kd over Kd 1 1 1): its uvs run v 1 at the top of the
# head to 0 at its bottom (OBJ's v up), so the image's upper half (red) colours the upper half.
write("tulip_head.png", png_rgba(8, 16, lambda x, y: RED if y < 8 else ORANGE))
write("tulip_textured.mtl", "# Wangscape test model: the stem green by Kd, the head by its image\n"
      "newmtl stem\nKd 0.10 0.60 0.10\n\nnewmtl head\nKd 1.00 1.00 1.00\nmap_Kd tulip_head.png\n")
body, _ = round_tulip(1, 0.5, 0.12)
write("tulip_textured.obj", "\n".join(
    ["# Wangscape test model: a round tulip whose head is coloured by an image (make_own_models.py)",
     "mtllib tulip_textured.mtl", "o tulip_textured"] + body) + "\n")


# A GLB with alpha leaves: three 1 m cards crossed at 60 degrees about the y axis (glTF: y up),
# each 0.8 m wide, normals along their faces; one 32 x 32 image held in the file: columns of 4
# pixels alternately opaque (red in the top quarter, orange below) and transparent blue.
def crossed_cards(width=0.8, height=1.0):
    import math
    positions, normals, uvs, indices = [], [], [], []
    for yaw_degrees in (0, 60, 120):
        yaw = math.radians(yaw_degrees)
        ax, az = math.cos(yaw), -math.sin(yaw)  # across the card
        nx, nz = math.sin(yaw), math.cos(yaw)   # its normal
        base = len(positions)
        for s, t in ((-0.5, 0.0), (0.5, 0.0), (0.5, 1.0), (-0.5, 1.0)):
            positions.append((s * width * ax, t * height, s * width * az))
            normals.append((nx, 0.0, nz))
            uvs.append((s + 0.5, 1.0 - t))  # glTF's v runs down the image
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    return positions, normals, uvs, indices


cross_image = png_rgba(32, 32, lambda x, y: CLEAR_BLUE if (x // 4) % 2 else (RED if y < 8 else ORANGE))
write("leaf_cross.glb", glb_bytes("leaf_cross", *crossed_cards(), cross_image,
                                  "Wangscape tests/data/models/make_own_models.py", roughness=0.8, material="leaf",
                                  sampler={"magFilter": 9728, "minFilter": 9728}))
