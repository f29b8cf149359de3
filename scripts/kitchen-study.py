#!/usr/bin/env python3
"""The equal-time study on the obvhs kitchen (issue 34): every method's error against an
independent reference at matched wall-clock time, set-up included (reading the glTF, the
contact split, building the BVH: everything the `render` process does).

Each method runs as the `render` example would for a user, once per time budget:
- the progressive modes and SPPM stop by themselves (`--time`, which counts from the first
  pass, so the script first measures each one's set-up with one pass and gives it
  `budget - set-up`);
- the one-pass modes (final gather, shadow rays, path tracer) are run on a ladder of sample
  and photon counts, and each budget takes the rung whose time is nearest.
Every run's process wall and CPU time are measured, and the tables say which time each error
comes with, so nothing is matched by hand.

What a budget matches (`--match`): the process's wall time (the default), or its CPU time,
`budget × threads` CPU-seconds. A renderer whose set-up keeps fewer cores busy (the contact
split runs at about 1.65× on two threads, the passes at 1.9×) uses less CPU in the same wall
time. With `--match cpu` each timed method runs a second time, its `--time` set from a fit of
CPU time = set-up + rate × pass time to its one-pass run and its first run at the wall
budget; that second run is kept. A ladder's rung is then the one nearest in CPU time.

Error: relative RMSE over the image against the reference (channel mean), with the
reference's own variance removed, sqrt(max(mean((o - r)^2) - mean(se_r^2), 0)) / mean(r);
also on 4×4-pixel means (the estimate's low-frequency error, with the per-pixel sampling
noise mostly averaged out) and the image mean's relative difference. The reference is
scripts/mitsuba-reference.py's .npy (mean and standard error per pixel); its noise is
reported so that the reader can see it is at least 3× below the errors it judges.

With several seeds the table gives each cell's mean and its standard error over the seeds,
and for each budget the leak-free method with the lowest mean per-pixel error is compared,
seed by seed, with the SPPM setting that is best on each measure: the mean paired difference,
its standard error, how many standard errors that is (t) and on how many seeds the leak-free
method was lower, per pixel and on 4×4 means.

`--rescore` re-scores the EXRs an earlier run kept in --out-dir against --reference (a less
noisy one, say) without rendering again.

Writes a Markdown table and a JSON of every run to --out-dir (default
target/kitchen/study); never into tracked files. Needs numpy and mitsuba (to read EXRs).

Usage: scripts/kitchen-study.py --reference target/kitchen/out/mitsuba.npy
       [--scene target/kitchen/kitchen.gltf] [--budgets 2,6,30] [--seeds 1] [--match wall|cpu]
       [--methods sppm,progressive,...] [--render target/release/examples/render]
       [--out-dir DIR] [--rescore]
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

# The progressive renderer with shadow rays, and with the contact gap the studies use.
PROGRESSIVE = ["--mode", "progressive", "--direct", "shadow-rays"]
GAP_1E4 = PROGRESSIVE + ["--contact-gap", "0.0001"]


def per_pass(photons, k=None):
    """Arguments for `photons` traced a pass and, when given, the pilot's k."""
    return ["--photons", str(photons)] + ([] if k is None else ["--k", str(k)])


# name -> (arguments, kind). "timed" runs take --time; "ladder" runs take each rung's args.
METHODS = {
    "sppm": (["--mode", "sppm"], "timed"),
    "progressive": (PROGRESSIVE, "timed"),
    "progressive-gap1e-4": (GAP_1E4, "timed"),
    # Two camera samples per pixel on each pass's photons, or fewer photons per pass: more
    # camera samples per second, where per-pixel error is mostly pixel sampling noise. With
    # fewer photons, a smaller k keeps the gather volume from widening (session 18); below
    # 25,000 (session 19) k is scaled so that the volume holds about as many photons of a
    # pass as k = 50 did with 25,000.
    "progressive-gap1e-4-spp2": (GAP_1E4 + ["--spp", "2"], "timed"),
    "progressive-gap1e-4-photons50k": (GAP_1E4 + per_pass(50000), "timed"),
    "progressive-gap1e-4-photons25k": (GAP_1E4 + per_pass(25000), "timed"),
    "progressive-gap1e-4-photons25k-k50": (GAP_1E4 + per_pass(25000, 50), "timed"),
    "progressive-gap1e-4-photons25k-k35": (GAP_1E4 + per_pass(25000, 35), "timed"),
    "progressive-gap1e-4-photons35k-k50": (GAP_1E4 + per_pass(35000, 50), "timed"),
    "progressive-gap1e-4-photons15k-k30": (GAP_1E4 + per_pass(15000, 30), "timed"),
    "progressive-gap1e-4-photons15k-k50": (GAP_1E4 + per_pass(15000, 50), "timed"),
    "progressive-gap1e-4-photons10k-k20": (GAP_1E4 + per_pass(10000, 20), "timed"),
    "progressive-gap1e-4-k50": (GAP_1E4 + ["--k", "50"], "timed"),
    "progressive-gap1e-4-k25": (GAP_1E4 + ["--k", "25"], "timed"),
    "progressive-gap1e-4-k12": (GAP_1E4 + ["--k", "12"], "timed"),
    "progressive-gap1e-4-photons35k-k25": (GAP_1E4 + per_pass(35000, 25), "timed"),
    "sppm-photons50k": (["--mode", "sppm"] + per_pass(50000), "timed"),
    "sppm-photons25k": (["--mode", "sppm"] + per_pass(25000), "timed"),
    "sppm-photons12k": (["--mode", "sppm"] + per_pass(12500), "timed"),
    "progressive-crease": (PROGRESSIVE + ["--maps", "crease"], "timed"),
    "progressive-photons": (["--mode", "progressive", "--direct", "photons"], "timed"),
    # Camera-driven emission (issue 36): the same runs with --emission camera.
    "sppm-camera": (["--mode", "sppm", "--emission", "camera"], "timed"),
    "progressive-camera": (PROGRESSIVE + ["--emission", "camera"], "timed"),
    "progressive-gap1e-4-camera": (GAP_1E4 + ["--emission", "camera"], "timed"),
    "progressive-gather": (
        ["--mode", "progressive", "--gather-rays", "4", "--spp", "4"], "timed"),
    "final-gather": (["--mode", "final-gather"], "ladder"),
    "shadow-rays": (["--mode", "shadow-rays"], "ladder"),
    "path-trace": (["--mode", "path-trace"], "ladder"),
}

# Rungs of the one-pass methods, cheapest first.
LADDERS = {
    "final-gather": [["--spp", str(s), "--photons", str(p)] for s, p in
                     [(1, 50000), (2, 100000), (4, 200000), (8, 300000), (16, 500000),
                      (32, 1000000), (64, 2000000)]],
    "shadow-rays": [["--spp", str(s), "--photons", str(p)] for s, p in
                    [(4, 100000), (8, 300000), (16, 1000000), (32, 3000000), (64, 8000000),
                     (128, 16000000)]],
    "path-trace": [["--spp", str(s)] for s in [4, 8, 16, 32, 64, 128, 256]],
}


def read_exr(path):
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    return np.array(mi.Bitmap(path))[:, :, :3].astype(np.float64).mean(2)


def down(a, b):
    h, w = a.shape
    return a[:h // b * b, :w // b * b].reshape(h // b, b, w // b, b).mean((1, 3))


def errors(ours, ref, ref_var):
    """Relative RMSE at full resolution and on 4×4 means (reference noise removed), and
    the mean's relative difference."""
    out = {}
    for b in (1, 4):
        o, r, v = down(ours, b), down(ref, b), down(ref_var, b) / (b * b)
        mse = ((o - r) ** 2).mean() - v.mean()
        out[f"rmse{b}"] = math.sqrt(max(mse, 0.0)) / ref.mean()
        out[f"noise{b}"] = math.sqrt(v.mean()) / ref.mean()
    out["mean"] = ours.mean() / ref.mean() - 1.0
    return out


def run(args, name, extra, seed, tag):
    out = os.path.join(args.out_dir, f"{name}-{tag}-s{seed}.exr")
    stats = out[:-4] + ".json"
    size = f"{args.width}x{args.height}"
    cmd = [args.render, "--scene", args.scene, "--size", size, "--seed", str(seed),
           "--threads", str(args.threads), "--out", out, "--stats-json", stats] + extra
    t0 = time.monotonic()
    r0 = os.times()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - t0
    r1 = os.times()
    if done.returncode != 0:
        raise SystemExit(f"error: {' '.join(cmd)} failed:\n{done.stderr}")
    cpu = (r1.children_user - r0.children_user) + (r1.children_system - r0.children_system)
    with open(stats) as f:
        figures = json.load(f)
    return out, wall, cpu, figures


def spent(args, rec):
    """What a run spent, in budget seconds: its wall time, or its CPU time over the threads."""
    return rec["wall"] if args.match == "wall" else rec["cpu"] / args.threads


def cpu_matched_time(args, budget, one_pass, timed):
    """The `--time` (seconds of passes) at which a timed run's process CPU time comes to
    `budget × threads`, from two runs of it: one pass (`one_pass`) and a first try at the wall
    budget (`timed`), each (CPU seconds, stats). The process's CPU time is taken as a set-up
    part plus a rate per second of passes, the two fitted to those runs."""
    (cpu1, fig1), (cpu2, fig2) = one_pass, timed
    p1, p2 = fig1["seconds"]["total"], fig2["seconds"]["total"]
    rate = (cpu2 - cpu1) / (p2 - p1) if p2 - p1 > 0.05 else 0.95 * args.threads
    rate = min(max(rate, 0.25), float(args.threads))
    setup_cpu = cpu1 - rate * p1
    return max((budget * args.threads - setup_cpu) / rate, 0.01)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--reference", required=True)
    p.add_argument("--scene", default="target/kitchen/kitchen.gltf")
    p.add_argument("--render", default="target/release/examples/render")
    p.add_argument("--budgets", default="2,6,30")
    p.add_argument("--seeds", default="1")
    p.add_argument("--methods", default=",".join(METHODS))
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--out-dir", default="target/kitchen/study")
    p.add_argument("--match", choices=("wall", "cpu"), default="wall",
                   help="what a budget of B seconds matches: the process's wall time (wall), "
                        "or its CPU time, B × threads CPU-seconds (cpu)")
    p.add_argument("--rescore", action="store_true",
                   help="score the EXRs of the run kept in --out-dir against --reference")
    args = p.parse_args()
    if not os.path.exists(args.scene):
        print(f"skipped: {args.scene} not found (make it with scripts/kitchen-gltf.py)")
        return
    os.makedirs(args.out_dir, exist_ok=True)
    ref_mean, ref_se = np.load(args.reference).astype(np.float64)
    ref = ref_mean.mean(2)
    ref_var = (ref_se ** 2).mean(2) / 3.0
    args.height, args.width = ref.shape
    if args.rescore:
        return rescore(args, ref, ref_var)
    unknown = [m for m in args.methods.split(",") if m not in METHODS]
    if unknown:
        raise SystemExit(f"error: --methods: unknown {', '.join(unknown)}; "
                         f"the methods are {', '.join(METHODS)}")
    try:
        budgets = [float(b) for b in args.budgets.split(",")]
        seeds = [int(s) for s in args.seeds.split(",")]
    except ValueError as e:
        raise SystemExit(f"error: --budgets takes seconds and --seeds integers, comma-separated ({e})")
    if not all(b > 0 and math.isfinite(b) for b in budgets):
        raise SystemExit(f"error: --budgets must be positive seconds, not {args.budgets}")
    records = []
    # Seed by seed, every method in turn: a stretch of the day when the machine runs slower
    # (other tenants of the host) then slows every method alike rather than one method's runs.
    for seed in seeds:
        for name in args.methods.split(","):
            base, kind = METHODS[name]
            if kind == "timed":
                _, wall1, cpu1, fig1 = run(args, name, base + ["--passes", "1"], seed, "setup")
                setup = max(wall1 - fig1["seconds"]["total"], 0.0)
                for b in budgets:
                    t = max(b - setup, 0.01)
                    timed = base + ["--time", f"{t:.3f}"]
                    out, wall, cpu, fig = run(args, name, timed, seed, f"t{b:g}")
                    if args.match == "cpu":
                        t = cpu_matched_time(args, b, (cpu1, fig1), (cpu, fig))
                        timed = base + ["--time", f"{t:.3f}"]
                        out, wall, cpu, fig = run(args, name, timed, seed, f"t{b:g}")
                    e = errors(read_exr(out), ref, ref_var)
                    rec = dict(method=name, seed=seed, budget=b, match=args.match, wall=wall,
                               cpu=cpu, setup=setup,
                               passes=fig.get("passes"), maps=fig.get("map_count"),
                               exr=os.path.basename(out), **e)
                    records.append(rec)
                    print(json.dumps(rec), flush=True)
            else:
                for i, rung in enumerate(LADDERS[name]):
                    out, wall, cpu, fig = run(args, name, base + rung, seed, f"r{i}")
                    e = errors(read_exr(out), ref, ref_var)
                    rec = dict(method=name, seed=seed, rung=" ".join(rung), match=args.match,
                               wall=wall, cpu=cpu,
                               maps=fig.get("map_count"), exr=os.path.basename(out), **e)
                    records.append(rec)
                    print(json.dumps(rec), flush=True)
                    if spent(args, rec) > 1.5 * max(budgets):
                        break
    with open(os.path.join(args.out_dir, "study.json"), "w") as f:
        json.dump(records, f, indent=1)
    write_table(args, records, budgets)


def rescore(args, ref, ref_var):
    """Scores the kept run's EXRs against the reference given now; writes study.json and
    study.md again (the run's first ones are kept as study-first.*)."""
    path = os.path.join(args.out_dir, "study.json")
    if not os.path.exists(path):
        raise SystemExit(f"error: --rescore: no {path} (run the study into --out-dir first)")
    with open(path) as f:
        records = json.load(f)
    # Runs kept before --match existed matched wall time.
    matched = {r.get("match", "wall") for r in records}
    if len(matched) != 1:
        raise SystemExit(f"error: --rescore: {path} mixes budgets matched by {sorted(matched)}")
    args.match = matched.pop()
    for suffix in ("json", "md"):
        first = os.path.join(args.out_dir, f"study-first.{suffix}")
        current = os.path.join(args.out_dir, f"study.{suffix}")
        if not os.path.exists(first) and os.path.exists(current):
            os.replace(current, first)
    for rec in records:
        name = rec.get("exr")
        if name is None and "budget" in rec:
            # Runs kept before the EXR's name was recorded: the name the run gave it.
            name = f"{rec['method']}-t{rec['budget']:g}-s{rec['seed']}.exr"
        if name is None:
            raise SystemExit(f"error: --rescore: {rec['method']} seed {rec['seed']} "
                             f"({rec.get('rung')}) has no EXR recorded; run it again")
        rec.update(errors(read_exr(os.path.join(args.out_dir, name)), ref, ref_var))
    with open(path, "w") as f:
        json.dump(records, f, indent=1)
    # The timed runs' budgets; a study of ladders alone takes --budgets.
    budgets = sorted({r["budget"] for r in records if "budget" in r}) or \
        [float(b) for b in args.budgets.split(",")]
    write_table(args, records, budgets)


def mean_and_error(values):
    """The mean of `values` and its standard error (0 for a single value)."""
    m = float(np.mean(values))
    if len(values) < 2:
        return m, 0.0
    return m, float(np.std(values, ddof=1) / math.sqrt(len(values)))


def timed_by_method(records, budget):
    """The timed runs at `budget`, by method and then by seed."""
    by = {}
    for r in records:
        if r.get("budget") == budget:
            by.setdefault(r["method"], {})[r["seed"]] = r
    return by


def best_leak_free(by):
    """Of the timed methods in `by`, the leak-free one (not SPPM, not crease maps, which leak
    light around the objects resting on surfaces) with the lowest mean per-pixel error."""
    names = [m for m in by if not m.startswith("sppm") and "crease" not in m]
    return min(names, key=lambda m: np.mean([r["rmse1"] for r in by[m].values()]), default=None)


def interpolated(args, runs, at):
    """A ladder's errors at `at` budget seconds, interpolated (log error against log time)
    between the two of `runs` (one seed's rungs) around it; None outside the ladder."""
    runs = sorted(runs, key=lambda r: spent(args, r))
    below = [r for r in runs if spent(args, r) <= at]
    above = [r for r in runs if spent(args, r) > at]
    if not below or not above:
        return None
    lo, hi = below[-1], above[0]
    f = math.log(at / spent(args, lo)) / math.log(spent(args, hi) / spent(args, lo))

    def between(a, b):
        # An error at or below the reference's noise scores 0, which has no logarithm: linear
        # in log time then.
        if a <= 0 or b <= 0:
            return a + f * (b - a)
        return math.exp(math.log(a) + f * (math.log(b) - math.log(a)))

    return {k: between(lo[k], hi[k]) for k in ("rmse1", "rmse4")}


def ladder_lines(args, records, budgets):
    """Per budget and ladder: the ladder interpolated, seed by seed, to the CPU or wall time
    of the best leak-free timed method's own run, and that method against it, paired."""
    lines = []
    ladders = list(dict.fromkeys(r["method"] for r in records if "rung" in r))
    for b in budgets:
        by = timed_by_method(records, b)
        ours = best_leak_free(by)
        if ours is None:
            continue
        for name in ladders:
            at = {}
            for seed, rec in by[ours].items():
                e = interpolated(args, [r for r in records if r["method"] == name
                                        and r.get("seed") == seed and "rung" in r],
                                 spent(args, rec))
                if e is not None:
                    at[seed] = (rec, e)
            if len(at) < 2:
                continue
            parts = []
            for key, label in (("rmse1", "per pixel"), ("rmse4", "4×4 means")):
                diff = [rec[key] - e[key] for rec, e in at.values()]
                mean_e = np.mean([e[key] for _, e in at.values()])
                parts.append(f"{label} {mean_e:.4f}, {ours} − it = {paired(diff)}")
            lines.append(f"- ~{b:g} s, {name} interpolated to {ours}'s time: " + "; ".join(parts))
    return lines


def paired_lines(records, budgets):
    """Per budget: the leak-free method with the lowest mean per-pixel error against the SPPM
    setting with the lowest mean error on each measure, seed by seed (one leak-free setting
    held against SPPM at its best for that measure)."""
    lines = []
    for b in budgets:
        by = timed_by_method(records, b)
        ours = best_leak_free(by)
        sppm_names = [m for m in by if m.startswith("sppm")]
        if ours is None or not sppm_names:
            continue
        for key, label in (("rmse1", "per pixel"), ("rmse4", "4×4 means")):
            theirs = min(sppm_names, key=lambda m: np.mean([r[key] for r in by[m].values()]))
            seeds = sorted(set(by[ours]) & set(by[theirs]))
            if len(seeds) < 2:
                continue
            diff = [by[ours][s][key] - by[theirs][s][key] for s in seeds]
            lines.append(f"- ~{b:g} s, {label}: {ours} − {theirs} = {paired(diff, ' seeds')}")
    return lines


def paired(diff, unit=""):
    """Paired differences as `mean ± standard error (t = …; lower on n of N<unit>)`."""
    m, se = mean_and_error(diff)
    t = m / se if se > 0 else float("inf")
    lower = sum(d < 0 for d in diff)
    return f"{m:+.4f} ± {se:.4f} (t = {t:+.1f}; lower on {lower} of {len(diff)}{unit})"


def nearest_rungs(args, ladder, budget):
    """Seed by seed, the rung of a ladder's runs nearest `budget` (by ratio)."""
    by_seed = {}
    for r in ladder:
        by_seed.setdefault(r["seed"], []).append(r)
    return [min(runs, key=lambda r: abs(math.log(spent(args, r) / budget)))
            for _, runs in sorted(by_seed.items())]


def write_table(args, records, budgets):
    unit = "s" if args.match == "wall" else f"CPU-s / {args.threads}"
    lines = [f"Budgets match each run's {'wall' if args.match == 'wall' else 'CPU'} time.",
             f"Reference noise (relative RMS): {records[0]['noise1']:.4f} per pixel, "
             f"{records[0]['noise4']:.4f} on 4×4 means.", "",
             "| method | " + " | ".join(f"~{b:g} s" for b in budgets) + " |",
             "|---|" + "---|" * len(budgets)]
    for name in dict.fromkeys(r["method"] for r in records):
        mine = [r for r in records if r["method"] == name]
        cells = []
        for b in budgets:
            near = [r for r in mine if r.get("budget") == b] or nearest_rungs(args, mine, b)
            w = np.mean([spent(args, r) for r in near])
            (e1, s1), (e4, s4) = (mean_and_error([r[k] for r in near]) for k in ("rmse1", "rmse4"))
            m = np.mean([r["mean"] for r in near])
            if len(near) > 1:
                cells.append(f"{e1:.4f} ± {s1:.4f} / {e4:.4f} ± {s4:.4f} "
                             f"({w:.2f} {unit}, {100 * m:+.1f} %, {len(near)} seeds)")
            else:
                cells.append(f"{e1:.4f} / {e4:.4f} ({w:.2f} {unit}, {100 * m:+.1f} %)")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    pairs = paired_lines(records, budgets)
    if pairs:
        lines += ["", "Best leak-free method against best SPPM setting, paired by seed "
                  "(mean difference ± its standard error):"] + pairs
    ladders = ladder_lines(args, records, budgets)
    if ladders:
        lines += ["", "The one-pass modes interpolated between the rungs around the best "
                  "leak-free method's own run, paired by seed:"] + ladders
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.out_dir, "study.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    sys.exit(main())
