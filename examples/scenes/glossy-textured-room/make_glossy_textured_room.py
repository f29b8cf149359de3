#!/usr/bin/env python3
"""Writes glossy-textured-room.gltf, its .bin and its textures beside this script.

The textured room (../textured-room, same geometry, camera and light) with glTF 2.0's
metallic-roughness materials at work: a varnished tiled floor (the same base-colour texture;
a metallicRoughnessTexture making the tiles roughness 0.15 and the grout 1; a normal map that
bevels each tile's edges into the grout; KHR_materials_specular's specularTexture, in the
alpha channel, weakening the grout's specular layer to a quarter), a glossy red wall
(dielectric, roughness 0.45), a brushed-aluminium right wall (metal, roughness 0.2) and glTF's
default matte white elsewhere (metallic 0, roughness 1: a Fresnel layer with F0 = 0.04). The
floor has no NORMAL or TANGENT: a loader makes flat normals and MikkTSpace tangents.
Python 3 standard library only; the output is byte-for-byte the same on every run.

    python3 examples/scenes/glossy-textured-room/make_glossy_textured_room.py
"""

import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ beside the textured room's script
sys.path.insert(0, os.path.join(HERE, "..", "textured-room"))
import make_textured_room as room  # noqa: E402

SIZE = 64  # texels across one repeat of the floor texture (2 x 2 tiles), as floor.png
BEVEL = 0.5  # the sideways component of a bevelled edge's normal


def png(width, height, rows, channels):
    """An 8-bit PNG (RGB for 3 channels, RGBA for 4) from rows of texel tuples."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    colour_type = {3: 2, 4: 6}[channels]
    header = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
            + chunk(b"IEND", b""))


def is_grout(i):
    """The grout lines of floor.png: the first and last texel of each tile."""
    return i % (SIZE // 2) in (0, SIZE // 2 - 1)


def edge_lean(i):
    """A tile's bevel along one axis: -1 at its first texel (sloping down towards the lower
    coordinate), +1 at its last, 0 inside."""
    k = i % (SIZE // 2)
    return -1 if k == 0 else (1 if k == SIZE // 2 - 1 else 0)


def metallic_roughness():
    """Green = roughness: 0.15 on the tiles, 1 in the grout; blue = metalness 0."""
    rows = [[(0, 255 if is_grout(x) or is_grout(y) else 38, 0) for x in range(SIZE)]
            for y in range(SIZE)]
    return png(SIZE, SIZE, rows, 3)


def normals():
    """Tangent-space normals (+x along u, +y up the image): each tile's edges lean towards the
    grout beside them (down its bevel), the grout and the tiles' faces point straight out."""
    rows = []
    for y in range(SIZE):
        row = []
        for x in range(SIZE):
            # Image rows grow downwards, so a tile's top row (first in y) slopes up the image.
            n = (BEVEL * edge_lean(x), -BEVEL * edge_lean(y), 1.0)
            length = math.sqrt(sum(c * c for c in n))
            row.append(tuple(round((c / length + 1.0) / 2.0 * 255.0) for c in n))
        rows.append(row)
    return png(SIZE, SIZE, rows, 3)


def specular():
    """Alpha = specular strength: 1 on the tiles, 0.25 in the grout (RGB unused, white)."""
    rows = [[(255, 255, 255, 64 if is_grout(x) or is_grout(y) else 255) for x in range(SIZE)]
            for y in range(SIZE)]
    return png(SIZE, SIZE, rows, 4)


MATERIALS = [
    {"name": "varnished tiles", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": 0}, "metallicFactor": 1.0, "roughnessFactor": 1.0,
        "metallicRoughnessTexture": {"index": 1}},
     "normalTexture": {"index": 2},
     "extensions": {"KHR_materials_specular": {"specularTexture": {"index": 3}}}},
    {"name": "matte white", "pbrMetallicRoughness": {
        "baseColorFactor": [0.75, 0.75, 0.75, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}},
    {"name": "glossy red", "pbrMetallicRoughness": {
        "baseColorFactor": [0.7, 0.12, 0.08, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.45}},
    room.MATERIALS[3],
    {"name": "brushed aluminium", "pbrMetallicRoughness": {
        "baseColorFactor": [0.91, 0.92, 0.92, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.2}},
]
IMAGES = [("floor.png", room.floor_texture), ("floor-mr.png", metallic_roughness),
          ("floor-normal.png", normals), ("floor-specular.png", specular)]


def build():
    room.room(MATERIALS, [{"source": i, "sampler": 0} for i in range(len(IMAGES))],
              [{"uri": name} for name, _ in IMAGES],
              ["KHR_materials_emissive_strength", "KHR_materials_specular"], HERE,
              "glossy-textured-room")
    for name, make in IMAGES:
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(make())


if __name__ == "__main__":
    build()
