#!/usr/bin/env python3
"""Converts the kitchen that ships in the obvhs crate (assets/kitchen.obj.zst + kitchen.mtl,
a Blender 3.6 OBJ) into a self-contained .gltf for checks of the contact split on a real
modelled interior (issue 33).

Every material becomes a double-sided Lambertian one (baseColorFactor = Kd, metallic 0,
roughness 1, KHR_materials_specular factor 0), one mesh primitive per material. Vertices stay as the OBJ gives them: every
face corner its own vertex (unwelded), no normals, no texture coordinates (flat shading, as
the Mitsuba reference renders it). Two KHR_lights_punctual point lamps hang under the
ceiling and a perspective camera looks at the countertops.

Python 3 standard library only; decompresses with the `zstd` command-line tool, or the
`zstandard` module when it is installed. Exits 0 with "skipped: kitchen not found in the
cargo registry" when the crate is not there. Never writes into tracked files: the default
output is target/kitchen/kitchen.gltf.

Usage: scripts/kitchen-gltf.py [--out PATH] [--lamp-candela CD] [--camera EX EY EZ TX TY TZ]
       [--aspect A] [--print-source]
"""

import argparse
import base64
import glob
import json
import os
import shutil
import struct
import subprocess
import sys

# Where the lamps hang (under the 2.44 m ceiling) and where the camera stands, in the OBJ's
# own coordinates (Y up, metres). The camera looks across the room at the L of countertops
# along the window wall and the left wall.
LAMPS = [(-0.3, 2.3, -0.6), (1.6, 2.3, 1.0)]
CAMERA_POSITION = (3.0, 1.6, 1.8)
CAMERA_TARGET = (-0.6, 0.8, -1.0)
CAMERA_YFOV_DEGREES = 50.0


def find_kitchen():
    """The (obj.zst, mtl) paths of the newest obvhs crate in the cargo registry, or None."""
    home = os.environ.get("CARGO_HOME", os.path.expanduser("~/.cargo"))
    pattern = os.path.join(home, "registry", "src", "*", "obvhs-*", "assets", "kitchen.obj.zst")
    found = sorted(glob.glob(pattern))
    if not found:
        return None
    obj = found[-1]
    mtl = os.path.join(os.path.dirname(obj), "kitchen.mtl")
    return (obj, mtl) if os.path.isfile(mtl) else None


def decompress(path):
    """The OBJ text of a .zst file."""
    if shutil.which("zstd"):
        return subprocess.run(
            ["zstd", "-dc", path], check=True, stdout=subprocess.PIPE
        ).stdout.decode("utf-8")
    try:
        import zstandard  # type: ignore
    except ImportError:
        sys.exit("error: neither the zstd tool nor the python zstandard module is available "
                 "(pip install zstandard)")
    with open(path, "rb") as f:
        return zstandard.ZstdDecompressor().stream_reader(f).read().decode("utf-8")


def read_mtl(path):
    """Material name -> Kd (r, g, b)."""
    kd = {}
    name = None
    with open(path, encoding="utf-8") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "newmtl":
                name = " ".join(parts[1:])
                kd[name] = (0.8, 0.8, 0.8)
            elif parts[0] == "Kd" and name is not None:
                kd[name] = tuple(min(max(float(x), 0.0), 1.0) for x in parts[1:4])
    return kd


def read_obj(text):
    """Material name -> flat list of triangle corner positions (fan-triangulated), in file
    order of first use."""
    positions = []
    by_material = {}
    current = "default"
    for line in text.splitlines():
        if line.startswith("v "):
            x, y, z = line.split()[1:4]
            positions.append((float(x), float(y), float(z)))
        elif line.startswith("usemtl"):
            current = line.split(None, 1)[1].strip()
        elif line.startswith("f "):
            corners = []
            for token in line.split()[1:]:
                i = int(token.split("/")[0])
                corners.append(positions[i - 1 if i > 0 else len(positions) + i])
            tris = by_material.setdefault(current, [])
            for k in range(1, len(corners) - 1):
                tris.extend((corners[0], corners[k], corners[k + 1]))
    return by_material


def look_at_quaternion(eye, target):
    """The rotation (x, y, z, w) turning a glTF camera (looking down -Z, +Y up) to look from
    `eye` at `target` with world +Y up."""
    def sub(a, b):
        return [a[i] - b[i] for i in range(3)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def norm(a):
        n = sum(x * x for x in a) ** 0.5
        return [x / n for x in a]

    back = norm(sub(eye, target))  # camera +Z
    right = norm(cross([0.0, 1.0, 0.0], back))  # camera +X
    up = cross(back, right)  # camera +Y
    # Rotation matrix columns: right, up, back.
    m = [[right[0], up[0], back[0]], [right[1], up[1], back[1]], [right[2], up[2], back[2]]]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 0.5 / (trace + 1.0) ** 0.5
        w = 0.25 / s
        x = (m[2][1] - m[1][2]) * s
        y = (m[0][2] - m[2][0]) * s
        z = (m[1][0] - m[0][1]) * s
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = 2.0 * (1.0 + m[0][0] - m[1][1] - m[2][2]) ** 0.5
        w = (m[2][1] - m[1][2]) / s
        x = 0.25 * s
        y = (m[0][1] + m[1][0]) / s
        z = (m[0][2] + m[2][0]) / s
    elif m[1][1] > m[2][2]:
        s = 2.0 * (1.0 + m[1][1] - m[0][0] - m[2][2]) ** 0.5
        w = (m[0][2] - m[2][0]) / s
        x = (m[0][1] + m[1][0]) / s
        y = 0.25 * s
        z = (m[1][2] + m[2][1]) / s
    else:
        s = 2.0 * (1.0 + m[2][2] - m[0][0] - m[1][1]) ** 0.5
        w = (m[1][0] - m[0][1]) / s
        x = (m[0][2] + m[2][0]) / s
        y = (m[1][2] + m[2][1]) / s
        z = 0.25 * s
    return [x, y, z, w]


def build_gltf(by_material, kd, lamp_candela, aspect, eye, target):
    buffer = bytearray()
    accessors, views, meshes_prims, materials = [], [], [], []
    for name, corners in by_material.items():
        if not corners:
            continue
        offset = len(buffer)
        for p in corners:
            buffer += struct.pack("<3f", *p)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(buffer) - offset,
                      "target": 34962})
        lo = [min(p[i] for p in corners) for i in range(3)]
        hi = [max(p[i] for p in corners) for i in range(3)]
        # Bounds as the f32 values actually stored.
        lo = [struct.unpack("<f", struct.pack("<f", v))[0] for v in lo]
        hi = [struct.unpack("<f", struct.pack("<f", v))[0] for v in hi]
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126,
                          "count": len(corners), "type": "VEC3", "min": lo, "max": hi})
        r, g, b = kd.get(name, (0.8, 0.8, 0.8))
        materials.append({"name": name, "doubleSided": True, "pbrMetallicRoughness": {
            "baseColorFactor": [r, g, b, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
            # Pure Lambertian: without this, glTF's Appendix B keeps a 4 % Fresnel layer.
            "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}})
        meshes_prims.append({"attributes": {"POSITION": len(accessors) - 1},
                             "material": len(materials) - 1, "mode": 4})
    nodes = [{"name": "kitchen", "mesh": 0}]
    lights = []
    for i, pos in enumerate(LAMPS):
        lights.append({"name": f"lamp{i}", "type": "point", "color": [1.0, 1.0, 1.0],
                       "intensity": lamp_candela})
        nodes.append({"name": f"lamp{i}", "translation": list(pos),
                      "extensions": {"KHR_lights_punctual": {"light": i}}})
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye),
                  "rotation": look_at_quaternion(eye, target)})
    return {
        "asset": {"version": "2.0", "generator": "photon-maps scripts/kitchen-gltf.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_specular"],
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": [{"name": "kitchen", "primitives": meshes_prims}],
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": CAMERA_YFOV_DEGREES * 3.141592653589793 / 180.0, "aspectRatio": aspect,
            "znear": 0.01}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(buffer), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(bytes(buffer)).decode("ascii")}],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join("target", "kitchen", "kitchen.gltf"),
                        help="where the .gltf goes (default target/kitchen/kitchen.gltf)")
    parser.add_argument("--lamp-candela", type=float, default=1500.0,
                        help="intensity of each point lamp in candela (default 1500; the "
                             "renderer's default light units make it 1500/683 W/sr)")
    parser.add_argument("--aspect", type=float, default=16.0 / 9.0,
                        help="the camera's aspect ratio (default 16:9)")
    parser.add_argument("--camera", type=float, nargs=6, metavar=("EX", "EY", "EZ", "TX", "TY", "TZ"),
                        default=list(CAMERA_POSITION) + list(CAMERA_TARGET),
                        help="camera position and the point it looks at (default: across the "
                             "room at the countertops; e.g. 0.3 0.45 0.2 -0.2 0.35 -1.2 looks "
                             "at the sink counter's front from close by)")
    parser.add_argument("--print-source", action="store_true",
                        help="print the found OBJ path and exit")
    args = parser.parse_args()
    found = find_kitchen()
    if found is None:
        print("skipped: kitchen not found in the cargo registry (obvhs-*/assets/kitchen.obj.zst)")
        return 0
    obj, mtl = found
    if args.print_source:
        print(obj)
        return 0
    by_material = read_obj(decompress(obj))
    kd = read_mtl(mtl)
    gltf = build_gltf(by_material, kd, args.lamp_candela, args.aspect, args.camera[:3], args.camera[3:])
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(gltf, f)
    triangles = sum(len(c) for c in by_material.values()) // 3
    print(f"wrote {args.out}: {triangles} triangles, {len(gltf['materials'])} materials, "
          f"{len(LAMPS)} lamps of {args.lamp_candela} cd, from {obj}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
