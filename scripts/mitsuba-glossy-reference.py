#!/usr/bin/env python3
"""Mitsuba 3 reference for glTF scenes with metallic-roughness materials (glTF 2.0 Appendix B),
e.g. target/glossy-check/glossy-box.gltf from scripts/glossy-box-gltf.py. Like
scripts/mitsuba-reference.py (whose scene reading, light units, camera and .npy output it
reuses), but every non-Lambertian material becomes a Python BSDF (`gltf_mr`, registered with
mi.register_bsdf) implementing Appendix B exactly:

    alpha = roughness^2, D = GGX, V = height-correlated Smith visibility,
    specular_brdf = V D, w = (1 - |V.H|)^5,
    metal_brdf = specular_brdf (base + (1 - base) w),
    dielectric_brdf = mix(base/pi, specular_brdf, 0.04 + 0.96 w),
    f = mix(dielectric_brdf, metal_brdf, metallic)

two-sided (both directions are mirrored to the side the incident direction is on, as our
renderer flips its normals to the side wo leaves to). Materials with KHR_materials_specular
factor 0 and metallic 0 stay Mitsuba's own two-sided `diffuse` (as ours reads them). Other
KHR_materials_ior / _specular values are refused (not implemented here).

Sampling (independent of ours on purpose): with probability 1/2 a cosine-weighted direction,
else a GGX half-vector drawn from D(h) cos(theta_h) (not visible normals) and reflected; the
pdf is the 50/50 mixture. The Python BSDF forces the scalar_rgb variant (the LLVM backend
fails to compile on this machine), so this is slow: about a few thousand paths per second.

`--self-test` checks the BSDF's eval/pdf/sample against a direct numpy implementation of
the formulas and by Monte Carlo (pdf integrates to 1; sampling's mean weight equals the
directional albedo by uniform quadrature) and exits.

Usage: scripts/mitsuba-glossy-reference.py SCENE.gltf --size 160x120 --spp 64 --passes 8 --out ref.exr
"""

import argparse
import importlib.util
import json
import math
import os
import sys
import time

import numpy as np

INV_PI = 1.0 / math.pi


def load_reference_module():
    here = os.path.dirname(os.path.abspath(__file__))
    spec = importlib.util.spec_from_file_location("mitsuba_reference", os.path.join(here, "mitsuba-reference.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# ---------------------------------------------------------------- the BRDF in plain Python

def brdf_local(base, metallic, alpha, wi, wo):
    """Appendix B's f (no cosine) for local unit wi, wo with both z > 0 (tuples)."""
    hx, hy, hz = wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]
    hn = math.sqrt(hx * hx + hy * hy + hz * hz)
    if hn == 0.0:
        return (0.0, 0.0, 0.0)
    hx, hy, hz = hx / hn, hy / hn, hz / hn
    a2 = alpha * alpha
    nh = hz
    t = nh * nh * (a2 - 1.0) + 1.0
    d = a2 * INV_PI / (t * t)
    nv, nl = wi[2], wo[2]
    v = 0.5 / (nl * math.sqrt(nv * nv * (1.0 - a2) + a2) + nv * math.sqrt(nl * nl * (1.0 - a2) + a2))
    spec = v * d
    vh = abs(wi[0] * hx + wi[1] * hy + wi[2] * hz)
    w = (1.0 - vh) ** 5
    fd = 0.04 + 0.96 * w
    out = []
    for c in base:
        metal = spec * (c + (1.0 - c) * w)
        diel = (1.0 - fd) * c * INV_PI + fd * spec
        out.append((1.0 - metallic) * diel + metallic * metal)
    return tuple(out)


def pdf_local(alpha, wi, wo):
    """The 50/50 mixture of cosine and D(h) cos(theta_h) / (4 |wo.h|)."""
    if wi[2] <= 0.0 or wo[2] <= 0.0:
        return 0.0
    hx, hy, hz = wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]
    hn = math.sqrt(hx * hx + hy * hy + hz * hz)
    p_cos = wo[2] * INV_PI
    if hn == 0.0:
        return 0.5 * p_cos
    hx, hy, hz = hx / hn, hy / hn, hz / hn
    a2 = alpha * alpha
    t = hz * hz * (a2 - 1.0) + 1.0
    d = a2 * INV_PI / (t * t)
    oh = abs(wo[0] * hx + wo[1] * hy + wo[2] * hz)
    p_spec = d * hz / (4.0 * oh) if oh > 0 else 0.0
    return 0.5 * p_cos + 0.5 * p_spec


def sample_local(alpha, wi, u_lobe, u1, u2):
    """A direction (local, maybe below) from the mixture, for wi above."""
    if u_lobe < 0.5:
        r = math.sqrt(u1)
        phi = 2.0 * math.pi * u2
        return (r * math.cos(phi), r * math.sin(phi), math.sqrt(max(0.0, 1.0 - u1)))
    tan2 = alpha * alpha * u1 / max(1e-12, 1.0 - u1)
    cos_h = 1.0 / math.sqrt(1.0 + tan2)
    sin_h = math.sqrt(max(0.0, 1.0 - cos_h * cos_h))
    phi = 2.0 * math.pi * u2
    h = (sin_h * math.cos(phi), sin_h * math.sin(phi), cos_h)
    d = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]
    return (2 * d * h[0] - wi[0], 2 * d * h[1] - wi[1], 2 * d * h[2] - wi[2])


# ---------------------------------------------------------------- numpy check of the formulas

def numpy_brdf(base, metallic, roughness, wi, wo):
    """Appendix B written out directly with numpy (V = view = wi, L = light = wo, N = z)."""
    base = np.asarray(base, dtype=np.float64)
    V, L = np.asarray(wi, float), np.asarray(wo, float)
    H = (V + L) / np.linalg.norm(V + L)
    alpha = roughness ** 2
    NdotL, NdotV, NdotH = L[2], V[2], H[2]
    D = alpha ** 2 * (NdotH > 0) / (np.pi * (NdotH ** 2 * (alpha ** 2 - 1) + 1) ** 2)
    Vis = 0.5 / (NdotL * np.sqrt(NdotV ** 2 * (1 - alpha ** 2) + alpha ** 2)
                 + NdotV * np.sqrt(NdotL ** 2 * (1 - alpha ** 2) + alpha ** 2))
    specular_brdf = Vis * D
    VdotH = abs(V @ H)
    metal_brdf = specular_brdf * (base + (1 - base) * (1 - VdotH) ** 5)
    fresnel = 0.04 + 0.96 * (1 - VdotH) ** 5
    dielectric_brdf = (1 - fresnel) * base / np.pi + fresnel * specular_brdf
    return (1 - metallic) * dielectric_brdf + metallic * metal_brdf


# ---------------------------------------------------------------- the Mitsuba BSDF

def register(mi):
    class GltfMR(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.base = (props.get("base_r", 1.0), props.get("base_g", 1.0), props.get("base_b", 1.0))
            self.metallic = props.get("metallic", 1.0)
            self.alpha = max(props.get("roughness", 1.0) ** 2, 1e-3)
            flags = (mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.DiffuseReflection
                     | mi.BSDFFlags.FrontSide | mi.BSDFFlags.BackSide)
            self.m_components = [flags]
            self.m_flags = flags

        @staticmethod
        def _local(si_wi, wo=None):
            wi = (si_wi[0], si_wi[1], si_wi[2])
            s = 1.0 if wi[2] >= 0 else -1.0
            wi = (wi[0], wi[1], s * wi[2])
            if wo is None:
                return s, wi, None
            return s, wi, (wo[0], wo[1], s * wo[2])

        def sample(self, ctx, si, sample1, sample2, active=True):
            bs = mi.BSDFSample3f()
            s, wi, _ = self._local(si.wi)
            if wi[2] <= 0.0:
                return bs, mi.Color3f(0.0)
            wo = sample_local(self.alpha, wi, float(sample1), float(sample2[0]), float(sample2[1]))
            if wo[2] <= 0.0:
                return bs, mi.Color3f(0.0)
            pdf = pdf_local(self.alpha, wi, wo)
            if not pdf > 0.0:
                return bs, mi.Color3f(0.0)
            f = brdf_local(self.base, self.metallic, self.alpha, wi, wo)
            k = wo[2] / pdf
            bs.wo = mi.Vector3f(wo[0], wo[1], s * wo[2])
            bs.pdf = pdf
            bs.eta = 1.0
            bs.sampled_type = int(mi.BSDFFlags.GlossyReflection)
            bs.sampled_component = 0
            return bs, mi.Color3f(f[0] * k, f[1] * k, f[2] * k)

        def eval(self, ctx, si, wo, active=True):
            _, wi, lo = self._local(si.wi, wo)
            if wi[2] <= 0.0 or lo[2] <= 0.0:
                return mi.Color3f(0.0)
            f = brdf_local(self.base, self.metallic, self.alpha, wi, lo)
            return mi.Color3f(f[0] * lo[2], f[1] * lo[2], f[2] * lo[2])

        def pdf(self, ctx, si, wo, active=True):
            _, wi, lo = self._local(si.wi, wo)
            return pdf_local(self.alpha, wi, lo)

        def eval_pdf(self, ctx, si, wo, active=True):
            _, wi, lo = self._local(si.wi, wo)
            if wi[2] <= 0.0 or lo[2] <= 0.0:
                return mi.Color3f(0.0), 0.0
            f = brdf_local(self.base, self.metallic, self.alpha, wi, lo)
            return mi.Color3f(f[0] * lo[2], f[1] * lo[2], f[2] * lo[2]), pdf_local(self.alpha, wi, lo)

        def to_string(self):
            return f"GltfMR[base={self.base}, metallic={self.metallic}, alpha={self.alpha}]"

    mi.register_bsdf("gltf_mr", lambda props: GltfMR(props))


def self_test(mi):
    rng = np.random.default_rng(7)
    worst = 0.0
    materials = [((0.9, 0.6, 0.3), 1.0, 0.3), ((0.2, 0.4, 0.8), 0.0, 0.5), ((0.5, 0.5, 0.5), 0.4, 0.8)]
    for base, metallic, roughness in materials:
        bsdf = mi.load_dict({"type": "gltf_mr", "base_r": base[0], "base_g": base[1], "base_b": base[2],
                             "metallic": metallic, "roughness": roughness})
        ctx = mi.BSDFContext()
        si = mi.SurfaceInteraction3f()
        for _ in range(20):
            a, b = rng.normal(size=3), rng.normal(size=3)
            a[2], b[2] = abs(a[2]), abs(b[2])
            a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
            for sign in (1, -1):  # the back side: both mirrored
                si.wi = mi.Vector3f(a[0], a[1], sign * a[2])
                got = np.array(bsdf.eval(ctx, si, mi.Vector3f(b[0], b[1], sign * b[2])))
                want = numpy_brdf(base, metallic, roughness, a, b) * b[2]
                worst = max(worst, float(np.max(np.abs(got - want) / np.maximum(want, 1e-12))))
            # opposite sides: zero
            si.wi = mi.Vector3f(*a)
            assert np.all(np.array(bsdf.eval(ctx, si, mi.Vector3f(b[0], b[1], -b[2]))) == 0)
        # Monte Carlo: pdf integrates to 1 and sampling's mean weight = directional albedo.
        for cos_i in (0.9, 0.5, 0.15):
            wi = (math.sqrt(1 - cos_i ** 2), 0.0, cos_i)
            si.wi = mi.Vector3f(*wi)
            n = 20000
            u = rng.random((n, 2))
            z = u[:, 0]  # uniform hemisphere
            r = np.sqrt(np.maximum(0, 1 - z * z))
            dirs = np.stack([r * np.cos(2 * np.pi * u[:, 1]), r * np.sin(2 * np.pi * u[:, 1]), z], 1)
            pdf_int = np.mean([bsdf.pdf(ctx, si, mi.Vector3f(*d)) for d in dirs]) * 2 * np.pi
            alb_q = np.mean([np.array(bsdf.eval(ctx, si, mi.Vector3f(*d))) for d in dirs], 0) * 2 * np.pi
            us = rng.random((n, 3))
            ws = []
            for k in range(n):
                bs, wgt = bsdf.sample(ctx, si, float(us[k, 0]), mi.Point2f(us[k, 1], us[k, 2]))
                ws.append(np.array(wgt))
            alb_s = np.mean(ws, 0)
            print(f"  base {base} metallic {metallic} roughness {roughness} cos_i {cos_i}: "
                  f"∫pdf = {pdf_int:.4f} (≤1; <1 where GGX reflections go below), albedo by "
                  f"quadrature {np.round(alb_q, 4)}, by sampling {np.round(alb_s, 4)}")
    print(f"eval against numpy Appendix B: worst relative difference {worst:.2e} over 120 pairs")
    return worst


def build_scene(ref, path, width, height, punctual_factor, workdir):
    import mitsuba as mi

    with open(path, encoding="utf-8") as f:
        gltf = json.load(f)
    buffers = ref.buffer_bytes(gltf, path)
    scene = {"type": "scene", "integrator": {"type": "path", "max_depth": -1, "rr_depth": 5}}
    lights = gltf.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    camera, shapes = {}, []

    def visit(node, world):
        if "mesh" in node:
            for prim in gltf["meshes"][node["mesh"]]["primitives"]:
                if prim.get("mode", 4) != 4:
                    continue
                p = ref.accessor(gltf, buffers, prim["attributes"]["POSITION"]).astype(np.float64)
                p = (world[:3, :3] @ p.T).T + world[:3, 3]
                if "indices" in prim:
                    idx = ref.accessor(gltf, buffers, prim["indices"]).reshape(-1, 3).astype(np.uint32)
                else:
                    idx = np.arange(len(p), dtype=np.uint32).reshape(-1, 3)
                mat = gltf["materials"][prim["material"]] if "material" in prim else {}
                pbr = mat.get("pbrMetallicRoughness", {})
                rgb = pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]
                ext = mat.get("extensions", {})
                metallic = pbr.get("metallicFactor", 1.0)
                roughness = pbr.get("roughnessFactor", 1.0)
                spec = ext.get("KHR_materials_specular", {})
                if metallic == 0 and spec.get("specularFactor", 1.0) == 0:
                    bsdf = {"type": "twosided", "bsdf": {"type": "diffuse",
                                                         "reflectance": {"type": "rgb", "value": list(rgb)}}}
                else:
                    if spec or "KHR_materials_ior" in ext or "KHR_materials_transmission" in ext:
                        sys.exit(f"material {mat.get('name')!r}: only Appendix B defaults are implemented")
                    bsdf = {"type": "gltf_mr", "base_r": rgb[0], "base_g": rgb[1], "base_b": rgb[2],
                            "metallic": float(metallic), "roughness": float(roughness)}
                ply = os.path.join(workdir, f"mesh{len(shapes)}.ply")
                ref.write_ply(ply, p.astype(np.float32), idx)
                shapes.append((ply, bsdf))
        e = node.get("extensions", {}).get("KHR_lights_punctual")
        if e is not None:
            light = lights[e["light"]]
            if light["type"] != "point":
                sys.exit("only point lights")
            colour = np.array(light.get("color", [1, 1, 1])) * light.get("intensity", 1.0) * punctual_factor
            scene[f"light{e['light']}"] = {"type": "point", "position": world[:3, 3].tolist(),
                                           "intensity": {"type": "rgb", "value": colour.tolist()}}
        if "camera" in node and not camera:
            cam = gltf["cameras"][node["camera"]]
            eye = world[:3, 3]
            camera.update(eye=eye, target=eye + world[:3, :3] @ np.array([0, 0, -1.0]),
                          up=world[:3, :3] @ np.array([0, 1.0, 0]),
                          fov=math.degrees(cam["perspective"]["yfov"]))

    ref.walk(gltf, visit)
    for k, (ply, bsdf) in enumerate(shapes):
        scene[f"shape{k}"] = {"type": "ply", "filename": ply, "face_normals": True, "bsdf": bsdf}
    scene["sensor"] = {
        "type": "perspective", "fov_axis": "y", "fov": camera["fov"],
        "to_world": mi.ScalarTransform4f().look_at(origin=camera["eye"].tolist(),
                                                   target=camera["target"].tolist(), up=camera["up"].tolist()),
        "film": {"type": "hdrfilm", "width": width, "height": height, "rfilter": {"type": "box"},
                 "pixel_format": "rgb"},
        "sampler": {"type": "independent"},
    }
    return mi.load_dict(scene)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?")
    parser.add_argument("--size", default="160x120")
    parser.add_argument("--spp", type=int, default=64, help="samples per pixel in all")
    parser.add_argument("--passes", type=int, default=8)
    parser.add_argument("--first-seed", type=int, default=1000)
    parser.add_argument("--light-units", choices=["mixed", "photometric", "viewer"], default="mixed")
    parser.add_argument("--out", default=os.path.join("target", "glossy-check", "mitsuba.exr"))
    parser.add_argument("--self-test", action="store_true")
    args = parser.parse_args()
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    register(mi)
    if args.self_test:
        worst = self_test(mi)
        sys.exit(0 if worst < 1e-4 else 1)
    ref = load_reference_module()
    width, height = (int(v) for v in args.size.lower().split("x"))
    factor = 1.0 if args.light_units == "viewer" else 1.0 / 683.0
    workdir = os.path.splitext(args.out)[0] + "-meshes"
    os.makedirs(workdir, exist_ok=True)
    scene = build_scene(ref, args.scene, width, height, factor, workdir)
    per_pass = max(1, args.spp // args.passes)
    images = []
    for k in range(args.passes):
        t = time.time()
        img = np.array(mi.render(scene, spp=per_pass, seed=args.first_seed + k))[:, :, :3]
        images.append(img)
        np.save(os.path.splitext(args.out)[0] + f"-pass{k}.npy", img.astype(np.float32))
        print(f"pass {k + 1}/{args.passes}: mean {img.mean():.5f} ({time.time() - t:.1f} s)", flush=True)
    stack = np.stack(images)
    mean = stack.mean(0)
    stderr = stack.std(0, ddof=1) / math.sqrt(len(images))
    mi.Bitmap(mean.astype(np.float32)).write(args.out)
    np.save(os.path.splitext(args.out)[0] + ".npy", np.stack([mean, stderr]).astype(np.float32))
    print(f"wrote {args.out} and its .npy: {width}x{height}, {per_pass * len(images)} spp, "
          f"mean rgb {mean.reshape(-1, 3).mean(0)}")


if __name__ == "__main__":
    main()
