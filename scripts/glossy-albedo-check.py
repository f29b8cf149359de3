#!/usr/bin/env python3
"""Directional albedo of the Python Appendix B BSDF of scripts/mitsuba-glossy-reference.py,
two ways: (1) a vectorized numpy quadrature of Appendix B (independent code: stratified
sampling of H from D(h)cos(h), f cos / pdf, 1M samples) and (2) the Mitsuba BSDF's own
sample() weights (N samples). They agree iff sample's directions, pdf and weights are
consistent with eval.

Usage: scripts/glossy-albedo-check.py [N]
"""
import importlib.util
import math
import os
import sys

import numpy as np


def appendix_b(base, metallic, roughness, V, L):
    a = roughness ** 2
    H = V + L
    H /= np.linalg.norm(H, axis=1, keepdims=True)
    NdotV, NdotL, NdotH = V[:, 2], L[:, 2], H[:, 2]
    D = a * a / (np.pi * (NdotH ** 2 * (a * a - 1) + 1) ** 2)
    Vis = 0.5 / (NdotL * np.sqrt(NdotV ** 2 * (1 - a * a) + a * a) + NdotV * np.sqrt(NdotL ** 2 * (1 - a * a) + a * a))
    s = (Vis * D)[:, None]
    w = ((1 - np.abs(np.sum(V * H, 1))) ** 5)[:, None]
    base = np.asarray(base)[None, :]
    metal = s * (base + (1 - base) * w)
    F = 0.04 + 0.96 * w
    diel = (1 - F) * base / np.pi + F * s
    return (1 - metallic) * diel + metallic * metal


def quadrature(base, metallic, roughness, cos_i, n=1_000_000, seed=3):
    """∫ f cos dω by sampling H ∝ D(h) cos h (pdf_L = D cos_h / (4 |V.H|)) plus cosine sampling,
    combined by the balance heuristic's one-sample mixture (independent of the BSDF class)."""
    rng = np.random.default_rng(seed)
    a = roughness ** 2
    V = np.tile([math.sqrt(1 - cos_i ** 2), 0.0, cos_i], (n, 1))
    u = rng.random((n, 3))
    # half of the samples cosine, half GGX
    cosine = u[:, 0] < 0.5
    u1, u2 = u[:, 1], u[:, 2]
    r = np.sqrt(u1)
    Lc = np.stack([r * np.cos(2 * np.pi * u2), r * np.sin(2 * np.pi * u2), np.sqrt(1 - u1)], 1)
    tan2 = a * a * u1 / (1 - u1)
    ch = 1 / np.sqrt(1 + tan2)
    sh = np.sqrt(1 - ch * ch)
    Hs = np.stack([sh * np.cos(2 * np.pi * u2), sh * np.sin(2 * np.pi * u2), ch], 1)
    Ls = 2 * np.sum(V * Hs, 1, keepdims=True) * Hs - V
    L = np.where(cosine[:, None], Lc, Ls)
    ok = L[:, 2] > 0
    L, V = L[ok], V[ok]
    H = (V + L) / np.linalg.norm(V + L, axis=1, keepdims=True)
    D = a * a / (np.pi * (H[:, 2] ** 2 * (a * a - 1) + 1) ** 2)
    pdf = 0.5 * L[:, 2] / np.pi + 0.5 * D * H[:, 2] / (4 * np.abs(np.sum(L * H, 1)))
    g = appendix_b(base, metallic, roughness, V, L) * (L[:, 2] / pdf)[:, None]
    full = np.zeros((n, 3))
    full[ok] = g
    return full.mean(0), full.std(0) / math.sqrt(n)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
    here = os.path.dirname(os.path.abspath(__file__))
    spec = importlib.util.spec_from_file_location("mgr", os.path.join(here, "mitsuba-glossy-reference.py"))
    mgr = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mgr)
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    mgr.register(mi)
    rng = np.random.default_rng(11)
    for base, metallic, roughness in [((0.9, 0.6, 0.3), 1.0, 0.3), ((0.2, 0.4, 0.8), 0.0, 0.5)]:
        bsdf = mi.load_dict({"type": "gltf_mr", "base_r": base[0], "base_g": base[1], "base_b": base[2],
                             "metallic": metallic, "roughness": roughness})
        ctx, si = mi.BSDFContext(), mi.SurfaceInteraction3f()
        for cos_i in (0.9, 0.5, 0.15):
            q, qse = quadrature(base, metallic, roughness, cos_i)
            si.wi = mi.Vector3f(-math.sqrt(1 - cos_i ** 2), 0.0, -cos_i)  # the back side
            us = rng.random((n, 3))
            ws = np.array([np.array(bsdf.sample(ctx, si, float(a), mi.Point2f(b, c))[1]) for a, b, c in us])
            s, sse = ws.mean(0), ws.std(0) / math.sqrt(n)
            t = (s - q) / np.sqrt(sse ** 2 + qse ** 2)
            print(f"base {base} m {metallic} r {roughness} cos {cos_i}: numpy {np.round(q, 4)}, "
                  f"BSDF.sample (back side) {np.round(s, 4)}, t {np.round(t, 1)}")


if __name__ == "__main__":
    main()
