#!/usr/bin/env python3
"""Independent reference for a glTF scene written by scripts/kitchen-gltf.py: renders it with
Mitsuba 3's `path` integrator (pip install mitsuba numpy) and writes an EXR plus a .npy of
per-pixel means and standard errors, for scripts/compare-reference.py.

What it reads of the glTF, and how it matches the project's renderer (examples/render):
- every mesh primitive (triangles, POSITION only, node transforms applied) with flat face
  normals, as the renderer shades a mesh without normals;
- materials: baseColorFactor as the albedo of a Lambertian BSDF on both sides (the file's
  materials are double-sided, metallic 0, roughness 1);
- KHR_lights_punctual point lamps: radiant intensity = colour x candela x punctual factor,
  the factor 1/683 W/lm of the renderer's default `--light-units mixed` (1 with `viewer`);
  see pm-trace/src/gltf/light.rs and units.rs;
- the first perspective camera: its position, -Z axis and +Y axis, vertical field of view
  yfov, at the image size given (the renderer uses the image's aspect ratio);
- pixels: box filter over the pixel, centre at +0.5 (the renderer's samples are each uniform
  over the pixel, a scrambled stratified sequence, and averaged).

Standard errors come from `--passes` independent renders with different seeds (each of
spp / passes samples per pixel): the per-pixel standard error of their mean. Beside the .npy a
.json records the samples per pixel and the seeds used, so that `--combine-with` can weight an
earlier run by its samples and refuse one whose seeds overlap this run's (their samples would
not be independent).

Usage: scripts/mitsuba-reference.py SCENE.gltf --size 320x180 --spp 1024 --out ref.exr
Not run in tests (CI has no Mitsuba).
"""

import argparse
import base64
import json
import math
import os
import struct
import sys

import numpy as np


def quat_to_matrix(q):
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def node_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
    m = np.eye(4)
    s = np.diag(node.get("scale", [1, 1, 1]) + [1])
    r = np.eye(4)
    r[:3, :3] = quat_to_matrix(node.get("rotation", [0, 0, 0, 1]))
    t = np.eye(4)
    t[:3, 3] = node.get("translation", [0, 0, 0])
    return t @ r @ s @ m


def walk(gltf, visit):
    """Calls visit(node, world matrix) for every node of the default scene."""
    scene = gltf["scenes"][gltf.get("scene", 0)]
    stack = [(n, np.eye(4)) for n in scene["nodes"]]
    while stack:
        index, parent = stack.pop()
        node = gltf["nodes"][index]
        world = parent @ node_matrix(node)
        visit(node, world)
        stack.extend((c, world) for c in node.get("children", []))


def buffer_bytes(gltf, path):
    out = []
    for b in gltf["buffers"]:
        uri = b["uri"]
        if uri.startswith("data:"):
            out.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            with open(os.path.join(os.path.dirname(path), uri), "rb") as f:
                out.append(f.read())
    return out


def accessor(gltf, buffers, index):
    a = gltf["accessors"][index]
    view = gltf["bufferViews"][a["bufferView"]]
    comps = {"SCALAR": 1, "VEC3": 3}[a["type"]]
    fmt = {5126: "f", 5125: "I", 5123: "H", 5121: "B"}[a["componentType"]]
    size = struct.calcsize(fmt)
    stride = view.get("byteStride", size * comps)
    data = buffers[view["buffer"]]
    base = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    values = [struct.unpack_from("<%d%s" % (comps, fmt), data, base + i * stride) for i in range(a["count"])]
    return np.array(values)


def write_ply(path, positions, triangles):
    """A binary little-endian PLY of the triangles (Mitsuba's ply loader)."""
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(positions)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(triangles)}\nproperty list uchar uint vertex_indices\nend_header\n"
    )
    faces = np.zeros(len(triangles), dtype=[("n", "u1"), ("v", "<u4", 3)])
    faces["n"] = 3
    faces["v"] = triangles
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(positions.astype("<f4").tobytes())
        f.write(faces.tobytes())


def build_scene(path, width, height, punctual_factor, max_depth, workdir):
    import mitsuba as mi

    with open(path, encoding="utf-8") as f:
        gltf = json.load(f)
    buffers = buffer_bytes(gltf, path)
    scene = {"type": "scene", "integrator": {"type": "path", "max_depth": max_depth, "rr_depth": 5}}
    lights = gltf.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    camera = {}
    shapes = []

    def visit(node, world):
        if "mesh" in node:
            for k, prim in enumerate(gltf["meshes"][node["mesh"]]["primitives"]):
                if prim.get("mode", 4) != 4:
                    continue
                p = accessor(gltf, buffers, prim["attributes"]["POSITION"]).astype(np.float64)
                p = (world[:3, :3] @ p.T).T + world[:3, 3]
                if "indices" in prim:
                    idx = accessor(gltf, buffers, prim["indices"]).reshape(-1, 3).astype(np.uint32)
                else:
                    idx = np.arange(len(p), dtype=np.uint32).reshape(-1, 3)
                mat = gltf["materials"][prim["material"]] if "material" in prim else {}
                rgb = mat.get("pbrMetallicRoughness", {}).get("baseColorFactor", [1, 1, 1, 1])[:3]
                specular = mat.get("extensions", {}).get("KHR_materials_specular", {})
                if mat.get("pbrMetallicRoughness", {}).get("metallicFactor", 1.0) != 0 \
                        or specular.get("specularFactor", 1.0) != 0:
                    # The renderer reads such a material by glTF's Appendix B (a Fresnel layer
                    # over the diffuse base); this reference renders it diffuse only.
                    sys.exit(f"material {mat.get('name', prim.get('material'))!r} is not pure "
                             "Lambertian (metallic 0 and KHR_materials_specular factor 0): "
                             "this reference renders diffuse surfaces only")
                ply = os.path.join(workdir, f"mesh{len(shapes)}.ply")
                write_ply(ply, p.astype(np.float32), idx)
                shapes.append((ply, rgb))
        ext = node.get("extensions", {}).get("KHR_lights_punctual")
        if ext is not None:
            light = lights[ext["light"]]
            if light["type"] != "point":
                sys.exit(f"error: only point lights are supported, not {light['type']}")
            colour = np.array(light.get("color", [1, 1, 1])) * light.get("intensity", 1.0) * punctual_factor
            scene[f"light{ext['light']}"] = {
                "type": "point",
                "position": world[:3, 3].tolist(),
                "intensity": {"type": "rgb", "value": colour.tolist()},
            }
        if "camera" in node and not camera:
            cam = gltf["cameras"][node["camera"]]
            eye = world[:3, 3]
            forward = world[:3, :3] @ np.array([0, 0, -1.0])
            up = world[:3, :3] @ np.array([0, 1.0, 0])
            camera.update(eye=eye, target=eye + forward, up=up,
                          fov=math.degrees(cam["perspective"]["yfov"]))

    walk(gltf, visit)
    if not camera:
        sys.exit("error: the file has no perspective camera")
    for k, (ply, rgb) in enumerate(shapes):
        scene[f"shape{k}"] = {
            "type": "ply", "filename": ply, "face_normals": True,
            "bsdf": {"type": "twosided", "bsdf": {
                "type": "diffuse", "reflectance": {"type": "rgb", "value": list(rgb)}}},
        }
    scene["sensor"] = {
        "type": "perspective",
        "fov_axis": "y",
        "fov": camera["fov"],
        "to_world": mi.ScalarTransform4f().look_at(
            origin=camera["eye"].tolist(), target=camera["target"].tolist(), up=camera["up"].tolist()),
        "film": {"type": "hdrfilm", "width": width, "height": height, "rfilter": {"type": "box"},
                 "pixel_format": "rgb"},
        "sampler": {"type": "independent"},
    }
    return mi.load_dict(scene)


def read_run_record(npy):
    """The samples per pixel and seeds of the run that wrote `npy` (its .json). A run made
    before the record was written has none: then it is taken to have as many samples as this
    run, as --combine-with required then, and its seeds cannot be checked (said so)."""
    path = os.path.splitext(npy)[0] + ".json"
    if not os.path.exists(path):
        print(f"warning: {path} is missing: {npy} is taken to have as many samples per pixel as "
              "this run, and its seeds are not checked against this run's", file=sys.stderr)
        return None
    with open(path) as f:
        record = json.load(f)
    if not isinstance(record.get("spp"), int) or record["spp"] <= 0:
        raise SystemExit(f"{path}: no positive 'spp'")
    return record


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--size", default="320x180")
    parser.add_argument("--spp", type=int, default=1024, help="samples per pixel in all")
    parser.add_argument("--passes", type=int, default=8, help="independent renders for the errors")
    parser.add_argument("--light-units", choices=["mixed", "photometric", "viewer"], default="mixed")
    parser.add_argument("--max-depth", type=int, default=-1, help="-1: Russian roulette only, as ours")
    parser.add_argument("--variant", default="scalar_rgb", help="Mitsuba variant (llvm_ad_rgb is faster where its JIT works; it failed to compile on the machine this was written on)")
    parser.add_argument("--out", default=os.path.join("target", "kitchen", "mitsuba.exr"))
    parser.add_argument("--first-seed", type=int, default=1000,
                        help="seed of the first pass (pass k renders with this + k)")
    parser.add_argument("--combine-with", metavar="NPY",
                        help="an earlier run's .npy, rendered with seeds that do not overlap "
                             "this run's: the output is both together, each weighted by its "
                             "samples per pixel (from the .json beside it)")
    args = parser.parse_args()
    out_base = os.path.splitext(args.out)[0]
    out_npy, out_json = out_base + ".npy", out_base + ".json"
    inputs = [args.scene] + ([args.combine_with, os.path.splitext(args.combine_with)[0] + ".json"]
                             if args.combine_with else [])
    for written in (args.out, out_npy, out_json):
        if any(os.path.abspath(written) == os.path.abspath(i) for i in inputs):
            raise SystemExit(f"--out would write {written}, which is an input: name another output")
    seeds = [args.first_seed, args.first_seed + args.passes - 1]
    earlier = None
    if args.combine_with:
        earlier = read_run_record(args.combine_with) or {"seeds": []}
        for first, last in earlier.get("seeds", []):
            if first <= seeds[1] and seeds[0] <= last:
                raise SystemExit(f"{args.combine_with} used seeds {first}-{last}, which overlap "
                                 f"this run's {seeds[0]}-{seeds[1]}: choose another --first-seed")
    import mitsuba as mi

    try:
        mi.set_variant(args.variant)
    except Exception:  # noqa: BLE001 (no LLVM on this machine)
        mi.set_variant("scalar_rgb")
    width, height = (int(v) for v in args.size.lower().split("x"))
    factor = 1.0 if args.light_units == "viewer" else 1.0 / 683.0
    workdir = os.path.splitext(args.out)[0] + "-meshes"
    os.makedirs(workdir, exist_ok=True)
    scene = build_scene(args.scene, width, height, factor, args.max_depth, workdir)
    per_pass = max(1, args.spp // args.passes)
    images = []
    for k in range(args.passes):
        img = np.array(mi.render(scene, spp=per_pass, seed=args.first_seed + k))[:, :, :3]
        images.append(img)
        print(f"pass {k + 1}/{args.passes}: mean {img.mean():.5f}", flush=True)
    stack = np.stack(images)
    mean = stack.mean(0)
    stderr = stack.std(0, ddof=1) / math.sqrt(args.passes) if args.passes > 1 else np.zeros_like(mean)
    spp = per_pass * args.passes
    record = {"spp": spp, "seeds": [seeds]}
    if args.combine_with:
        # Two independent estimates, each the mean of its own samples: the mean of all the
        # samples weights each by its count, and so does its standard error.
        earlier_mean, earlier_stderr = np.load(args.combine_with)
        if earlier_mean.shape != mean.shape:
            raise SystemExit(f"{args.combine_with}: {earlier_mean.shape[1]}x{earlier_mean.shape[0]}, "
                             f"not {width}x{height}")
        n0, n1 = earlier.get("spp", spp), spp
        mean = (n0 * earlier_mean + n1 * mean) / (n0 + n1)
        stderr = np.sqrt((n0 * earlier_stderr) ** 2 + (n1 * stderr) ** 2) / (n0 + n1)
        record = {"spp": n0 + n1, "seeds": earlier.get("seeds", []) + [seeds]}
        # Samples whose seeds no record gives (a run from before records), carried along.
        unrecorded = earlier.get("unrecorded_spp", 0) + (0 if "spp" in earlier else n0)
        if unrecorded:
            record["unrecorded_spp"] = unrecorded
        spp = n0 + n1
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    mi.Bitmap(mean.astype(np.float32)).write(args.out)
    np.save(out_npy, np.stack([mean, stderr]).astype(np.float32))
    with open(out_json, "w") as f:
        json.dump(record, f)
    print(f"wrote {args.out} and its .npy (mean, standard error): {width}x{height}, "
          f"{spp} spp, mean rgb {mean.reshape(-1, 3).mean(0)}")


if __name__ == "__main__":
    main()
