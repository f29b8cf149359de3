#!/usr/bin/env python3
"""A small glTF test scene for checking glTF 2.0's metallic-roughness BSDF (Appendix B)
against an independent Mitsuba 3 reference (scripts/mitsuba-glossy-reference.py).

A closed box 2 x 2 x 2 m (floor y=0, ceiling y=2, back wall z=-1, side walls x=+-1, front
wall z=+1 behind the camera), Lambertian walls (metallic 0, KHR_materials_specular factor 0),
a floor of rough metal (metallic 1, base [0.9, 0.6, 0.3], roughness 0.3), and a block
(0.6 x 0.6 x 0.6 m) of rough dielectric (metallic 0, roughness 0.5, base [0.2, 0.4, 0.8], no
specular extension: ior 1.5, f0 0.04). Two KHR_lights_punctual point lamps. All materials
doubleSided; positions only (flat shading), every triangle its own three vertices.

Python 3 standard library only.
Usage: scripts/glossy-box-gltf.py [--out target/glossy-check/glossy-box.gltf]
"""

import argparse
import base64
import json
import math
import os
import struct

LAMPS = [((-0.4, 1.7, 0.2), 60.0), ((0.5, 1.5, -0.4), 30.0)]  # position, candela
EYE = (0.0, 1.0, 0.95)
TARGET = (0.0, 0.55, -0.5)
YFOV_DEGREES = 55.0


def quad(a, b, c, d):
    return [a, b, c, a, c, d]


def box_faces(lo, hi, skip=()):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = {
        "-y": quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)),
        "+y": quad((x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)),
        "-z": quad((x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)),
        "+z": quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)),
        "-x": quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)),
        "+x": quad((x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)),
    }
    return {k: v for k, v in faces.items() if k not in skip}


def look_at_quaternion(eye, target):
    """(x, y, z, w) turning a glTF camera (-Z forward, +Y up) to look from eye at target."""
    def sub(a, b):
        return [a[i] - b[i] for i in range(3)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def norm(a):
        n = sum(x * x for x in a) ** 0.5
        return [x / n for x in a]

    back = norm(sub(eye, target))
    right = norm(cross([0.0, 1.0, 0.0], back))
    up = cross(back, right)
    m = [[right[0], up[0], back[0]], [right[1], up[1], back[1]], [right[2], up[2], back[2]]]
    trace = m[0][0] + m[1][1] + m[2][2]
    assert trace > 0, "camera too far from the default orientation for this simple conversion"
    s = 0.5 / (trace + 1.0) ** 0.5
    return [(m[2][1] - m[1][2]) * s, (m[0][2] - m[2][0]) * s, (m[1][0] - m[0][1]) * s, 0.25 / s]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join("target", "glossy-check", "glossy-box.gltf"))
    parser.add_argument("--aspect", type=float, default=4.0 / 3.0)
    args = parser.parse_args()

    room = box_faces((-1, 0, -1), (1, 2, 1))
    block = box_faces((-0.05, 0.0, -0.75), (0.55, 0.6, -0.15), skip=("-y",))
    lambert = lambda name, rgb: {  # noqa: E731
        "name": name, "doubleSided": True,
        "pbrMetallicRoughness": {"baseColorFactor": rgb + [1.0], "metallicFactor": 0.0,
                                 "roughnessFactor": 1.0},
        "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
    materials = [
        lambert("white", [0.75, 0.75, 0.75]),
        lambert("red", [0.7, 0.15, 0.1]),
        lambert("green", [0.15, 0.6, 0.2]),
        {"name": "rough-metal", "doubleSided": True, "pbrMetallicRoughness": {
            "baseColorFactor": [0.9, 0.6, 0.3, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.3}},
        {"name": "rough-dielectric", "doubleSided": True, "pbrMetallicRoughness": {
            "baseColorFactor": [0.2, 0.4, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5}},
    ]
    groups = [
        (room["+y"] + room["-z"] + room["+z"], 0),
        (room["-x"], 1),
        (room["+x"], 2),
        (room["-y"], 3),
        (sum(block.values(), []), 4),
    ]
    buffer = bytearray()
    accessors, views, prims = [], [], []
    for corners, mat in groups:
        offset = len(buffer)
        for p in corners:
            buffer += struct.pack("<3f", *p)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(buffer) - offset,
                      "target": 34962})
        lo = [float(min(p[i] for p in corners)) for i in range(3)]
        hi = [float(max(p[i] for p in corners)) for i in range(3)]
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126,
                          "count": len(corners), "type": "VEC3", "min": lo, "max": hi})
        prims.append({"attributes": {"POSITION": len(accessors) - 1}, "material": mat, "mode": 4})
    nodes = [{"name": "box", "mesh": 0}]
    lights = []
    for i, (pos, cd) in enumerate(LAMPS):
        lights.append({"name": f"lamp{i}", "type": "point", "color": [1.0, 1.0, 1.0], "intensity": cd})
        nodes.append({"name": f"lamp{i}", "translation": list(pos),
                      "extensions": {"KHR_lights_punctual": {"light": i}}})
    nodes.append({"name": "camera", "camera": 0, "translation": list(EYE),
                  "rotation": look_at_quaternion(EYE, TARGET)})
    gltf = {
        "asset": {"version": "2.0", "generator": "photon-maps scripts/glossy-box-gltf.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_specular"],
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": [{"name": "box", "primitives": prims}],
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": math.radians(YFOV_DEGREES), "aspectRatio": args.aspect, "znear": 0.01}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(buffer),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buffer)).decode()}],
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(gltf, f, indent=1)
    print(f"wrote {args.out}: {sum(len(c) for c, _ in groups) // 3} triangles, {len(lights)} lamps")


if __name__ == "__main__":
    main()
