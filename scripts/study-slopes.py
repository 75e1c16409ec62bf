#!/usr/bin/env python3
"""Error against time per scene and method from a `lumis study` folder, with
and without the reference's own noise.

    python3 scripts/study-slopes.py STUDY_DIR [--over DIR] [--metric mse|relmse] [--path path] [--refs DIR] [--ref-noise S]

A reference rendered by `path` has per-pixel variance of its own, so a
run's measured error is its true error plus that of the reference:
MSE = e + s. With --refs, a scene whose sidecar DIR/<scene>.txt says it was
made by `path` with N samples per pixel gets s from the study's own `path`
runs: a run with n samples has N/n times the reference's variance, so
s = MSE n / (N + n) (median over the runs). Otherwise s comes from a
least-squares fit of MSE(t) = v/t + s to the path runs (weighted by 1/MSE^2,
s >= 0). Where `path` does not converge (a delta light's caustic) nothing
is subtracted. --ref-noise S gives s for every scene instead (e.g. from an
independent `path` render of n spp: s = MSE(it, reference) n / (N + n)).
The corrected error of every run is MSE - s. Budgets are the runs'
measured seconds (pbrt-v4's runs are placed at their wall time). Per method
the table gives the geometric mean over seeds at each budget and the slope
of log error against log time (ordinary least squares over all runs).

--over DIR adds the runs of another study folder, each replacing the run
of STUDY_DIR with the same id (scene, setting, budget, seed): a setting
re-run on its own after a change (e.g. studies/caustics-gain.toml) is read
beside the other settings' runs it did not change.

Only the standard library; prints Markdown.
"""
import glob
import json
import math
import os
import sys
from collections import defaultdict


def fit_path(points):
    """Weighted least squares of y = v/t + s over (t, y); s clamped at 0."""
    sw = swx = swxx = swy = swxy = 0.0
    for t, y in points:
        w = 1.0 / (y * y)
        x = 1.0 / t
        sw += w
        swx += w * x
        swxx += w * x * x
        swy += w * y
        swxy += w * x * y
    det = sw * swxx - swx * swx
    if det <= 0:
        return 0.0, 0.0
    v = (sw * swxy - swx * swy) / det
    s = (swxx * swy - swx * swxy) / det
    if s < 0:
        v = swxy / swxx
        s = 0.0
    return v, s


def reference_spp(folder, scene):
    """The spp of a `path` reference from its sidecar `<scene>.txt` (line
    `samples per pixel: N`, the last such line); None if missing or not made
    by `path`."""
    try:
        with open(os.path.join(folder, scene + ".txt")) as f:
            text = f.read()
    except OSError:
        return None
    if "--integrator path" not in text:
        return None
    spp = None
    for line in text.splitlines():
        if line.startswith("samples per pixel:"):
            # the last one: a resumed reference appends a line per run
            word = line.split(":")[1].split()[0]
            spp = int(word) if word.isdigit() else spp
    return spp


def slope(points):
    xs = [math.log(t) for t, _ in points]
    ys = [math.log(y) for _, y in points]
    n = len(xs)
    if n < 2:
        return float("nan")
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0:
        return float("nan")
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def geo(values):
    return math.exp(sum(math.log(v) for v in values) / len(values))


def load_runs(folder):
    """The run records of a study folder: runs/*.json, or metrics.json (a
    committed report keeps its records there only)."""
    records = []
    for name in sorted(glob.glob(os.path.join(folder, "runs", "*.json"))):
        with open(name) as f:
            records.append(json.load(f))
    if not records and os.path.exists(os.path.join(folder, "metrics.json")):
        with open(os.path.join(folder, "metrics.json")) as f:
            records = json.load(f)["runs"]
    return records


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    folder = args[0]
    metric = "mse"
    path_name = "path"
    if "--metric" in args:
        metric = args[args.index("--metric") + 1]
    if "--path" in args:
        path_name = args[args.index("--path") + 1]
    refs = args[args.index("--refs") + 1] if "--refs" in args else None
    ref_noise = float(args[args.index("--ref-noise") + 1]) if "--ref-noise" in args else None
    records = load_runs(folder)
    if "--over" in args:
        over = args[args.index("--over") + 1]
        newer = load_runs(over)
        if not newer:
            sys.exit(f"no finished runs in {over}/runs or {over}/metrics.json")
        ids = {r["id"] for r in newer}
        records = [r for r in records if r["id"] not in ids] + newer
    runs = sorted(
        (r for r in records if r.get(metric) is not None and r.get("seconds")),
        key=lambda r: r["id"],
    )
    if not runs:
        sys.exit(f"no finished runs in {folder}/runs or {folder}/metrics.json")
    by_scene = defaultdict(list)
    for r in runs:
        by_scene[r["scene"]].append(r)
    for scene, rs in by_scene.items():
        path_pts = [(r["seconds"], r[metric]) for r in rs if r["setting"] == path_name]
        v, s = fit_path(path_pts) if len(path_pts) >= 3 else (0.0, 0.0)
        print(f"\n### {scene}\n")
        ref_spp = reference_spp(refs, scene) if refs else None
        if ref_noise is not None:
            s = ref_noise
            print(f"reference noise s = {s:.3g} ({metric}; given)\n")
        elif ref_spp is not None and path_pts:
            # The reference is `path` with ref_spp samples: a path run with n
            # has n/ref_spp times its variance, so E[MSE] = e (1 + n/ref_spp)
            # and the reference's share is MSE n / (ref_spp + n).
            shares = sorted(
                r[metric] * r["spp"] / (ref_spp + r["spp"]) for r in rs if r["setting"] == path_name
            )
            s = shares[len(shares) // 2]
            print(f"reference noise s = {s:.3g} ({metric}; `path` reference of {ref_spp} spp, "
                  f"median over {len(shares)} path runs)\n")
        elif path_pts and (v <= 0 or s > 0.5 * min(y for _, y in path_pts)):
            # `path` does not converge here (a delta light's caustic it
            # cannot find): its error is not the reference's noise.
            print(f"no correction: `{path_name}` does not converge on this scene\n")
            v, s = 0.0, 0.0
        else:
            print(f"reference noise s = {s:.3g} ({metric}; path fit v = {v:.3g})\n")
        budgets = sorted({r["budget"] for r in rs}, key=lambda b: float(b[1:-1]))
        print("| method | " + " | ".join(budgets) + " | slope | corrected | slope |")
        print("|---" * (2 * len(budgets) + 3) + "|")
        settings = []
        for r in rs:
            if r["setting"] not in settings:
                settings.append(r["setting"])
        last = {}
        for setting in settings:
            mine = [r for r in rs if r["setting"] == setting]
            raw, cor = [], []
            for b in budgets:
                at = [r for r in mine if r["budget"] == b]
                if not at:
                    raw.append(None)
                    cor.append(None)
                    continue
                raw.append(geo([r[metric] for r in at]))
                floor = 1e-3 * min(r[metric] for r in at)
                cor.append(geo([max(r[metric] - s, floor) for r in at]))
            pr = [(r["seconds"], r[metric]) for r in mine]
            pc = [(r["seconds"], max(r[metric] - s, 1e-3 * r[metric])) for r in mine]
            fmt = lambda xs: " | ".join("-" if x is None else f"{x:.2e}" for x in xs)
            print(f"| {setting} | {fmt(raw)} | {slope(pr):.2f} | {fmt(cor)} | {slope(pc):.2f} |")
            last[setting] = (raw[-1], cor[-1])
        if "progressive" in last:
            pr, pc = last["progressive"]
            others = [k for k in last if k != "progressive"]
            ratios = []
            for k in others:
                if last[k][0] and pr:
                    ratios.append(f"{k} {pr / last[k][0]:.2f} ({pc / last[k][1]:.2f} corrected)")
            print(f"\nprogressive / other at {budgets[-1]}: " + ", ".join(ratios))


if __name__ == "__main__":
    main()
