#!/usr/bin/env python3
"""Compares renders of ours (one or more EXRs of the same settings and different seeds)
with a reference written by scripts/mitsuba-reference.py (its .npy of per-pixel means and
standard errors), and reports:

- the mean relative difference over the image, (mean ours − mean ref) / mean ref, with its
  standard error (from the spread of our seeds and the reference's passes) and t = diff / se;
- per block (default 8×8 pixels): the relative difference of each block's mean, the worst
  blocks (most negative and most positive) with their t values, and how many blocks lie
  beyond 3 and 5 standard errors;
- the relative difference at a chosen pixel (--pixel X,Y), e.g. a countertop front.

Channel means are averaged over RGB. Needs numpy and mitsuba (only to read EXRs).
Usage: scripts/compare-reference.py REF.npy OURS.exr [OURS2.exr ...] [--block 8] [--pixel X,Y]
"""

import argparse
import math

import numpy as np


def read_exr(path):
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    return np.array(mi.Bitmap(path))[:, :, :3].astype(np.float64)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("reference", help="the .npy of scripts/mitsuba-reference.py")
    parser.add_argument("ours", nargs="+", help="our EXRs (different seeds, same settings)")
    parser.add_argument("--block", type=int, default=8)
    parser.add_argument("--pixel", action="append", default=[], help="X,Y to report (repeatable)")
    parser.add_argument("--label", default="ours")
    parser.add_argument("--worst", type=int, default=5)
    args = parser.parse_args()

    ref_mean, ref_se = np.load(args.reference).astype(np.float64)
    ref = ref_mean.mean(2)
    ref_var = (ref_se ** 2).mean(2) / 3.0  # variance of the channel mean (channels as independent)
    runs = np.stack([read_exr(p).mean(2) for p in args.ours])
    if runs.shape[1:] != ref.shape:
        raise SystemExit(f"error: sizes differ: ours {runs.shape[1:]}, reference {ref.shape}")
    k = len(runs)
    ours = runs.mean(0)

    def stats(o_runs, r, r_var):
        """Relative difference of the means and its standard error."""
        o_means = o_runs.reshape(k, -1).mean(1)
        o = o_means.mean()
        o_se2 = o_means.var(ddof=1) / k if k > 1 else 0.0
        rm = r.mean()
        rm_se2 = r_var.sum() / r.size ** 2
        rel = o / rm - 1.0
        se = math.sqrt(o_se2 / rm ** 2 + (o / rm ** 2) ** 2 * rm_se2)
        return rel, se

    rel, se = stats(runs, ref, ref_var)
    t = rel / se if se > 0 else float("inf")
    print(f"{args.label}: mean {ours.mean():.5f} against {ref.mean():.5f}: "
          f"relative difference {100 * rel:+.3f} % ± {100 * se:.3f} % (t = {t:+.1f}; {k} run(s))")

    b = args.block
    h, w = ref.shape
    rows = []
    for y in range(0, h - h % b, b):
        for x in range(0, w - w % b, b):
            r = ref[y:y + b, x:x + b]
            if r.mean() <= 1e-4:
                continue
            brel, bse = stats(runs[:, y:y + b, x:x + b], r, ref_var[y:y + b, x:x + b])
            rows.append((brel, bse, x, y))
    ts = np.array([r[0] / r[1] if r[1] > 0 else 0.0 for r in rows])
    print(f"  {len(rows)} blocks of {b}x{b}: {np.sum(np.abs(ts) > 3)} beyond 3 se, "
          f"{np.sum(np.abs(ts) > 5)} beyond 5 se; median |rel| {100 * np.median([abs(r[0]) for r in rows]):.2f} %")
    order = sorted(rows, key=lambda r: r[0])
    for label, chosen in (("darkest", order[:args.worst]), ("brightest", order[::-1][:args.worst])):
        text = ", ".join(f"({x},{y}) {100 * r:+.1f}% t={r / s if s > 0 else 0:+.1f}" for r, s, x, y in chosen)
        print(f"  {label} blocks: {text}")
    for p in args.pixel:
        x, y = (int(v) for v in p.split(","))
        print(f"  pixel ({x},{y}): ours {ours[y, x]:.4f} (runs {', '.join(f'{v:.4f}' for v in runs[:, y, x])}), "
              f"reference {ref[y, x]:.4f} ± {math.sqrt(ref_var[y, x]):.4f}")


if __name__ == "__main__":
    main()
