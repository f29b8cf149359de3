#!/usr/bin/env python3
"""Per-material comparison for scripts/mitsuba-glossy-reference.py: which glTF material the
pixel centre's camera ray hits first (Mitsuba ray cast), then for each material the mean of
our EXRs (several seeds) against the mean of the reference's per-pass images (the
`-passK.npy` files), with standard errors from the spread of seeds / passes, and t. Also the
ratio of per-pixel noise of ours (mean of our runs) to the reference's.

Usage: scripts/glossy-compare-regions.py SCENE.gltf 'REF-pass*.npy' OURS.exr [OURS2.exr ...]
"""

import argparse
import glob
import importlib.util
import json
import math
import os

import numpy as np


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("scene")
    parser.add_argument("passes", help="glob of the reference's per-pass .npy files")
    parser.add_argument("ours", nargs="+")
    args = parser.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    spec = importlib.util.spec_from_file_location("mgr", os.path.join(here, "mitsuba-glossy-reference.py"))
    mgr = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mgr)
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    mgr.register(mi)
    passes = np.stack([np.load(p).astype(np.float64) for p in sorted(glob.glob(args.passes))]).mean(3)
    ours = np.stack([np.array(mi.Bitmap(p))[:, :, :3].astype(np.float64) for p in args.ours]).mean(3)
    h, w = ours.shape[1:]
    ref_mod = mgr.load_reference_module()
    workdir = os.path.join(os.path.dirname(os.path.abspath(args.ours[0])), "regions-meshes")
    os.makedirs(workdir, exist_ok=True)
    scene = mgr.build_scene(ref_mod, args.scene, w, h, 1 / 683, workdir)
    with open(args.scene, encoding="utf-8") as f:
        gltf = json.load(f)
    names = [gltf["materials"][p["material"]]["name"] for m in gltf["meshes"] for p in m["primitives"]]
    sensor = scene.sensors()[0]
    label = np.full((h, w), -1)
    for y in range(h):
        for x in range(w):
            ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f((x + 0.5) / w, (y + 0.5) / h), mi.Point2f(0.5))
            si = scene.ray_intersect(ray)
            if si.is_valid():
                label[y, x] = int(si.shape.id().replace("shape", ""))
    ko, kr = len(ours), len(passes)
    print(f"{ko} runs of ours, {kr} reference passes")
    o_px_se = ours.std(0, ddof=1) / math.sqrt(ko)
    r_px_se = passes.std(0, ddof=1) / math.sqrt(kr)
    print(f"per-pixel standard error (median over pixels): ours {np.median(o_px_se):.3e}, "
          f"reference {np.median(r_px_se):.3e}, ratio ours/ref {np.median(o_px_se / np.maximum(r_px_se, 1e-12)):.2f}")
    regions = [("whole image", np.ones((h, w), bool))]
    for k in sorted(set(label.ravel()) - {-1}):
        regions.append((f"{names[k]} (shape{k})", label == k))
    for name, mask in regions:
        o = ours[:, mask].mean(1)
        r = passes[:, mask].mean(1)
        om, rm = o.mean(), r.mean()
        ose, rse = o.std(ddof=1) / math.sqrt(ko), r.std(ddof=1) / math.sqrt(kr)
        rel = om / rm - 1
        se = math.sqrt((ose / rm) ** 2 + (om * rse / rm ** 2) ** 2)
        print(f"  {name:28s} {mask.sum():6d} px: ours {om:.5f} ± {ose:.5f}, ref {rm:.5f} ± {rse:.5f}: "
              f"{100 * rel:+.2f} % ± {100 * se:.2f} % (t = {rel / se:+.1f})")


if __name__ == "__main__":
    main()
