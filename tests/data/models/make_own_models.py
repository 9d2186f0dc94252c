"""Writes Wangscape's own test models beside this script (run it again after a change):
tulip.obj + tulip.mtl: a green stem and a red head, colours by MTL Kd only (issue 38's tulip);
leaf_card.gltf + leaf_card.bin + leaf_card.png: a vertical 1 m card, y up (glTF), whose image
holds an opaque left half (red top quarter, orange below) and a transparent blue right half,
with alphaMode MASK: the blue must never show, the red must be at the top."""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def png_rgba(width, height, pixel):
    """An 8-bit RGBA PNG; pixel(column, row) gives (r, g, b, a), row 0 at the top."""
    raw = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


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
