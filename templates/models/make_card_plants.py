#!/usr/bin/python3
"""Writes the example user plants beside this script (run it again after a change): three
vegetation assets of the kind DCC tools and game libraries export, crossed alpha cards with one
texture each, as self-contained GLB files (y up, metres, ground contact at the origin):

  card_plants/fern_0.glb, fern_1.glb, fern_2.glb: three cards crossed at 60 degrees (plus two
  tilted outward), 0.9 to 1.2 m tall, a fern frond painted into a 128 x 256 RGBA image (a stalk,
  leaflets that taper toward the tip, two greens), alphaMode MASK at 0.5.

They stand for a user's own plants in templates/scenes/card-plants.toml and the README's picture.
Wangscape's own (same licence as Wangscape); nothing is downloaded."""
import json
import math
import os
import struct
import zlib

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "card_plants")


def png_rgba(width, height, pixel):
    """An 8-bit RGBA PNG; pixel(column, row) gives (r, g, b, a), row 0 at the top (the test models'
    script, tests/data/models/make_own_models.py, writes its images with it too)."""
    raw = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def frond(seed):
    """A fern frond's pixel function on a 128 x 256 image: u in [-1, 1] across, t in [0, 1] up."""
    leaflets = 14 + seed * 2
    bend = 0.08 * (seed - 1)

    def pixel(x, y):
        u = (x + 0.5) / 64 - 1
        t = 1 - (y + 0.5) / 256
        u -= bend * t * t  # the frond leans a little
        half = 0.95 * math.sin(math.pi * min(1.0, t * 1.15)) ** 0.8 * (1 - 0.55 * t)  # its outline
        stalk = abs(u) < 0.035 + 0.02 * (1 - t)
        if stalk and t < 0.98:
            return (70, 110, 40, 255)
        if abs(u) > half or t < 0.08:
            return (60, 100, 40, 0)
        # Leaflets: bands slanting up from the stalk, gaps between them.
        phase = (t * leaflets - abs(u) * 1.2) % 1.0
        if phase > 0.8:
            return (60, 100, 40, 0)
        light = 0.75 + 0.25 * math.cos(phase * math.pi)  # each leaflet's midrib lighter
        young = t > 0.7
        g = (95 if young else 120) * light + (25 if young else 0)
        return (int(45 * light + (30 if young else 0)), int(min(255, g)), int(30 * light), 255)
    return pixel


def cards(height, seed):
    """Positions, normals, uvs and indices of the crossed cards: three upright at 60 degrees and two
    leaning outward, each 0.7 of the height wide."""
    positions, normals, uvs, indices = [], [], [], []
    width = 0.7 * height
    layout = [(0, 0.0), (60, 0.0), (120, 0.0), (30 + 20 * seed, 0.45), (210 + 20 * seed, 0.45)]
    for yaw_degrees, lean in layout:
        yaw = math.radians(yaw_degrees)
        ax, az = math.cos(yaw), -math.sin(yaw)  # across the card (y up, z toward the viewer: glTF)
        nx, nz = math.sin(yaw), math.cos(yaw)   # its normal
        top = height * (0.85 if lean else 1.0)
        out = top * lean                        # the top leans out along the normal
        base = len(positions)
        for (s, t) in ((-0.5, 0.0), (0.5, 0.0), (0.5, 1.0), (-0.5, 1.0)):
            positions.append((s * width * ax + t * out * nx, t * top, s * width * az + t * out * nz))
            normals.append((nx, 0.0, nz))
            uvs.append((s + 0.5, 1.0 - t))  # glTF's v runs down the image
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    return positions, normals, uvs, indices


def glb_bytes(name, positions, normals, uvs, indices, image, generator, alpha_cutoff=0.5, roughness=0.9,
              material="frond", sampler=None):
    """A self-contained GLB of one mesh node `name` (y up): one primitive with its RGBA PNG `image`
    held in the binary chunk, alphaMode MASK at `alpha_cutoff`, double-sided (the test models'
    script, tests/data/models/make_own_models.py, writes its GLB with it too)."""
    parts = [b"".join(struct.pack("<3f", *p) for p in positions), b"".join(struct.pack("<3f", *n) for n in normals),
             b"".join(struct.pack("<2f", *t) for t in uvs), b"".join(struct.pack("<H", i) for i in indices), image]
    views, blob = [], b""
    for part in parts:
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(part)})
        blob += part + b"\0" * (-len(part) % 4)
    xs, ys, zs = zip(*positions)
    gltf = {
        "asset": {"version": "2.0", "generator": generator},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": name}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [{"name": material, "doubleSided": True, "alphaMode": "MASK", "alphaCutoff": alpha_cutoff,
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0,
                                                "roughnessFactor": roughness}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [sampler or {"magFilter": 9729, "minFilter": 9987}],
        "images": [{"bufferView": 4, "mimeType": "image/png"}],
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]},
            {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": len(uvs), "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
    }
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + blob
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def glb(name, height, seed):
    positions, normals, uvs, indices = cards(height, seed)
    data = glb_bytes(name, positions, normals, uvs, indices, png_rgba(128, 256, frond(seed)),
                     "Wangscape templates/models/make_card_plants.py")
    os.makedirs(HERE, exist_ok=True)
    with open(os.path.join(HERE, name + ".glb"), "wb") as f:
        f.write(data)


if __name__ == "__main__":
    for k, height in enumerate((1.0, 1.2, 0.9)):
        glb("fern_%d" % k, height, k)
