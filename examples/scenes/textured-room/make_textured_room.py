#!/usr/bin/env python3
"""Writes textured-room.gltf, textured-room.bin and floor.png beside this script.

A closed 4 m x 2.6 m x 4 m room: a tiled floor (a base-colour texture repeated 4 x 4), a red
wall, white walls and ceiling, and an emissive ceiling panel (KHR_materials_emissive_strength),
seen by a perspective camera. Python 3 standard library only; the output is byte-for-byte the
same on every run.

    python3 examples/scenes/textured-room/make_textured_room.py
"""

import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
W, H, D = 4.0, 2.6, 4.0
CENTRE = (W / 2, H / 2, D / 2)


def png_rgb(width, height, rows):
    """An 8-bit RGB PNG from rows of (r, g, b) codes."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
            + chunk(b"IEND", b""))


def floor_texture(size=64):
    """2 x 2 tiles, light and dark oak, each with a darker grout line and a faint grain."""
    light, dark, grout = (196, 160, 112), (140, 98, 60), (70, 60, 50)
    rows = []
    for y in range(size):
        row = []
        for x in range(size):
            tile = (x * 2 // size + y * 2 // size) % 2
            base = light if tile == 0 else dark
            if x % (size // 2) in (0, size // 2 - 1) or y % (size // 2) in (0, size // 2 - 1):
                base = grout
            grain = int(8 * math.sin(0.9 * y + 0.15 * x))
            row.append(tuple(max(0, min(255, c + grain)) for c in base))
        rows.append(row)
    return png_rgb(size, size, rows)


def facing_inward(corners):
    """The corners in counter-clockwise order seen from the room's centre (glTF's front)."""
    a, b, c = corners[0], corners[1], corners[2]
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    to_centre = [CENTRE[i] - a[i] for i in range(3)]
    inward = sum(n[i] * to_centre[i] for i in range(3)) > 0
    return corners if inward else corners[::-1]


def quad(corners, uvs=None, normal_to_centre=True):
    corners = facing_inward(corners) if normal_to_centre else corners
    return {"positions": corners, "uvs": uvs}


MATERIALS = [
    {"name": "tiled floor", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 1.0}},
    {"name": "white", "pbrMetallicRoughness": {
        "baseColorFactor": [0.75, 0.75, 0.75, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}},
    {"name": "red", "pbrMetallicRoughness": {
        "baseColorFactor": [0.7, 0.12, 0.08, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}},
    {"name": "panel", "pbrMetallicRoughness": {
        "baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
     "emissiveFactor": [1.0, 0.9, 0.75],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 6.0}}},
]
"""Materials by index: the floor (0), white walls and ceiling (1), the red wall (2), the
emissive panel (3); the right wall uses index 4 when there is one, else the white one."""


def build():
    room(MATERIALS, [{"source": 0, "sampler": 0}], [{"uri": "floor.png"}],
         ["KHR_materials_emissive_strength"], HERE, "textured-room")
    with open(os.path.join(HERE, "floor.png"), "wb") as f:
        f.write(floor_texture())


def room(materials, textures, images, extensions_used, out_dir, stem):
    """Writes out_dir/stem.gltf and out_dir/stem.bin: the room with these materials (indexed as
    MATERIALS is), textures and images (written by the caller)."""
    floor = [(0, 0, 0), (0, 0, D), (W, 0, D), (W, 0, 0)]
    floor_uv = [(0, 0), (0, 4), (4, 4), (4, 0)]
    # The floor's texture coordinates follow its corners, so set them before any reordering.
    floor_corners = facing_inward(floor)
    if floor_corners is not floor:
        floor_uv = floor_uv[::-1]
    p = 0.6  # half the panel's side
    y = H - 0.001  # 1 mm under the ceiling, facing down
    panel = [(W / 2 - p, y, D / 2 - p), (W / 2 + p, y, D / 2 - p), (W / 2 + p, y, D / 2 + p),
             (W / 2 - p, y, D / 2 + p)]
    # Facing down: counter-clockwise seen from below.
    n_y = ((panel[1][2] - panel[0][2]) * (panel[2][0] - panel[0][0])
           - (panel[1][0] - panel[0][0]) * (panel[2][2] - panel[0][2]))
    if n_y > 0:
        panel = panel[::-1]
    parts = [
        ("floor", {"positions": floor_corners, "uvs": floor_uv}, 0),
        ("ceiling", quad([(0, H, 0), (W, H, 0), (W, H, D), (0, H, D)]), 1),
        ("red wall", quad([(0, 0, 0), (0, H, 0), (0, H, D), (0, 0, D)]), 2),
        ("right wall", quad([(W, 0, 0), (W, 0, D), (W, H, D), (W, H, 0)]), 4 if len(materials) > 4 else 1),
        ("back wall", quad([(0, 0, 0), (W, 0, 0), (W, H, 0), (0, H, 0)]), 1),
        ("front wall", quad([(0, 0, D), (0, H, D), (W, H, D), (W, 0, D)]), 1),
        ("panel", {"positions": panel, "uvs": None}, 3),
    ]
    blob = bytearray()
    views, accessors, meshes, nodes = [], [], [], []

    def add(data, fmt, count, kind, target, minmax=None):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        acc = {"bufferView": len(views) - 1, "componentType": fmt, "count": count, "type": kind}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    for name, q, material in parts:
        pos = q["positions"]
        data = b"".join(struct.pack("<3f", *c) for c in pos)
        lo = [min(c[i] for c in pos) for i in range(3)]
        hi = [max(c[i] for c in pos) for i in range(3)]
        attributes = {"POSITION": add(data, 5126, 4, "VEC3", 34962, (lo, hi))}
        if q["uvs"]:
            attributes["TEXCOORD_0"] = add(b"".join(struct.pack("<2f", *t) for t in q["uvs"]),
                                           5126, 4, "VEC2", 34962)
        indices = add(struct.pack("<6H", 0, 1, 2, 0, 2, 3), 5123, 6, "SCALAR", 34963)
        meshes.append({"name": name, "primitives": [
            {"attributes": attributes, "indices": indices, "material": material}]})
        nodes.append({"name": name, "mesh": len(meshes) - 1})

    # The camera near the front wall, looking at the back wall, tilted 2 degrees up
    # (glTF cameras look along their local -z).
    tilt = math.radians(2.0)
    nodes.append({"name": "camera", "camera": 0, "translation": [W / 2, 1.3, D - 0.05],
                  "rotation": [math.sin(tilt / 2), 0.0, 0.0, math.cos(tilt / 2)]})
    gltf = {
        "asset": {"version": "2.0", "generator": "photon-maps make_textured_room.py"},
        "extensionsUsed": extensions_used,
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": math.radians(80.0), "aspectRatio": 1.0, "znear": 0.01}}],
        "textures": textures,
        "samplers": [{"wrapS": 10497, "wrapT": 10497, "magFilter": 9729, "minFilter": 9987}],
        "images": images,
        "buffers": [{"uri": stem + ".bin", "byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(os.path.join(out_dir, stem + ".bin"), "wb") as f:
        f.write(bytes(blob))
    with open(os.path.join(out_dir, stem + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    build()
