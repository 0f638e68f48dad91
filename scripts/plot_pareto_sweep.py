#!/usr/bin/python3
"""Plots and tabulates the Pareto study run as a sweep (benchmarks/pareto_sweep.py) from its HDF5
file, and compares it with docs/benchmarks.md's tables by ratios (the machines differ, the
ratios should not).

    python3 scripts/plot_pareto_sweep.py out/pareto_sweep.h5 [OUT_DIR] [--docs docs/benchmarks.md]
        [--csv out/pareto/pareto.csv ...]

For each scene: each run's cost (the sum of its per-step times over its simulated time, in
seconds per simulated second: the wall clock of step() alone, as pareto.cpp times its stepping
loop; of a run repeated for `min_time`, the fastest repetition's, as pareto.cpp takes), its error
(the RMS distance of its end positions to the finer RK4 reference's, over the bounding-box
diagonal of the start: trajectory_error) and its energy drift ((E(T) - E(0)) over the
reference's largest kinetic energy). Writes OUT_DIR/pareto_<scene>.png (as
scripts/plot_pareto.py draws docs/images/pareto_<scene>.png) and prints, per error level, the
cheapest setting and its cost relative to the cheapest setting at 1e-1, beside the same from
docs/benchmarks.md, and from each pareto.cpp output given with --csv (its cheapest setting's cost
over its own cost at 1e-1: several runs of pareto.cpp show its run-to-run spread). Needs h5py
and matplotlib (Debian's python3-h5py, python3-matplotlib).

The per-step times are taken in Python around each step() call, so they include the binding's
call (about 1 us, docs/python.md): negligible on the cloths (0.1 ms and more per step), dominant on
the 20-point chain, the 64-point net and the 2-point orbit, whose explicit steps take well under
1 us in C++. Compare the cloths' ratios."""

import argparse
import json
import math
import os
import re
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_pareto  # noqa: E402: the study's own plot and front, shared

THRESHOLDS = plot_pareto.THRESHOLDS


def read(path):
    """{scene: {"points": [...], "ref": {...}, "reference_change": x}} from the sweep's file."""
    scenes = {}
    with h5py.File(path, "r") as f:
        runs = f["runs"]
        groups = [runs[k] for k in runs]
        by_scene = {}
        for g in groups:
            name = g.attrs.get("name", "")
            if name.count("/") < 2:
                continue
            scene, family, setting = name.split("/", 2)
            by_scene.setdefault(scene, []).append((family, setting, g))
        for scene, entries in by_scene.items():
            refs = {s: g for fam, s, g in entries if fam == "Reference"}
            if "reference/2" not in refs or refs["reference/2"].attrs["status"] != "ok":
                print(f"{scene}: no finished reference run; left out", file=sys.stderr)
                continue
            fine = refs["reference/2"]
            x_ref = fine["final_positions"][()]
            start = fine["positions"][0]
            diagonal = float(np.linalg.norm(start.max(axis=0) - start.min(axis=0)))
            kinetic_max = float(np.max(fine["steps/kinetic_energy"][()]))
            change = math.nan
            if "reference" in refs and refs["reference"].attrs["status"] == "ok":
                change = error(refs["reference"]["final_positions"][()], x_ref, diagonal)
            points, other = [], []
            for family, setting, g in entries:
                if family == "Reference":
                    continue
                status = g.attrs["status"]
                dt = float(g.attrs["dt"])
                steps = int(g.attrs["final_step"])
                if "loop_seconds" in g:  # each repetition's loop; the fastest is the cost
                    seconds = float(np.min(g["loop_seconds"][()]))
                elif "steps" in g:
                    seconds = float(np.sum(g["steps/time"][()]))
                else:
                    seconds = math.nan
                p = {"scene": scene, "family": family, "setting": setting, "dt": dt,
                     "status": status, "steps": steps}
                if status != "ok":
                    other.append(p)
                    continue
                p["cost"] = seconds / (dt * steps)
                p["error"] = error(g["final_positions"][()], x_ref, diagonal)
                energy = g["steps/total_energy"][()]
                p["drift"] = (energy[-1] - g.attrs["initial_energy"]) / max(kinetic_max, 1e-300)
                if not p["error"] <= 1:
                    p["status"] = "diverged"
                    other.append(p)
                    continue
                points.append(p)
            scenes[scene] = {"points": points, "other": other, "change": change,
                             "ref": {"points": start.shape[0],
                                     "springs": fine.attrs.get("num_springs", "?"),
                                     "end_time": float(fine.attrs["dt"]) *
                                     int(fine.attrs["final_step"]),
                                     "still_error": error(start, x_ref, diagonal)},
                             "spec": json.loads(f.attrs.get("spec", "{}") or "{}")}
    return scenes


def error(x, reference, diagonal):
    return math.sqrt(np.sum((x - reference) ** 2) / x.shape[0]) / diagonal


def cheapest(points):
    rows = []
    for t in THRESHOLDS:
        below = [p for p in points if p["error"] <= t]
        rows.append((t, min(below, key=lambda p: p["cost"]) if below else None))
    return rows


def docs_tables(path):
    """{scene: [(threshold, setting, cost, error)]} from docs/benchmarks.md's generated
    tables."""
    tables, scene = {}, None
    if not os.path.exists(path):
        return tables
    with open(path) as handle:
        for line in handle:
            heading = re.match(r"### (\w+)$", line.strip())
            if heading:
                scene = heading.group(1)
            row = re.match(r"\| (\de-\d\d) \| (.+?) \| ([\d.e+-]+) \| ([\d.e+-]+) \|", line)
            if row and scene:
                tables.setdefault(scene, []).append((float(row.group(1)), row.group(2),
                                                     float(row.group(3)), float(row.group(4))))
    return tables


def csv_cheapest(path):
    """{scene: [(threshold, point or None)]} from a pareto.cpp pareto.csv: its ok points with an
    error of at most 1, cheapest per error level."""
    by_scene = {}
    for row in plot_pareto.read(path):
        if row["status"] != "ok":
            continue
        p = dict(row, dt=float(row["dt"]), cost=float(row["cost"]), error=float(row["error"]))
        if p["error"] <= 1:
            by_scene.setdefault(p["scene"], []).append(p)
    return {scene: cheapest(points) for scene, points in by_scene.items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results")
    parser.add_argument("out", nargs="?", default="out/pareto_sweep")
    parser.add_argument("--docs", default=os.path.join(os.path.dirname(__file__), "..", "docs",
                                                       "benchmarks.md"))
    parser.add_argument("--csv", action="append", default=[],
                        help="a pareto.cpp pareto.csv to compare with (repeatable)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    scenes = read(args.results)
    documented = docs_tables(args.docs)
    runs = [csv_cheapest(path) for path in args.csv]
    for scene, data in scenes.items():
        png = os.path.join(args.out, f"pareto_{scene}.png")
        plot_pareto.plot(scene, data["points"], data["ref"], png)
        print(f"\n### {scene}: {len(data['points'])} runs plotted, {len(data['other'])} not "
              f"(diverged or skipped); references differ by {data['change']:.2g}; {png}")
        print("| error at most | cheapest setting (sweep) | its error | cost / cost at 1e-1 | "
              "docs: cheapest setting | docs: its error | docs: cost / cost at 1e-1 |" +
              "".join(f" csv {k + 1}: cheapest setting | csv {k + 1}: cost / cost at 1e-1 |"
                      for k in range(len(runs))))
        print("|---:|---|---:|---:|---|---:|---:|" + "---|---:|" * len(runs))
        mine = cheapest(data["points"])
        theirs = {t: (s, c, e) for t, s, c, e in documented.get(scene, [])}
        base = mine[0][1]["cost"] if mine[0][1] else math.nan
        docs_base = theirs.get(THRESHOLDS[0], (None, math.nan, math.nan))[1]
        for t, p in mine:
            setting = plot_pareto.setting(p) if p else "-"
            ratio = p["cost"] / base if p else math.nan
            err = p["error"] if p else math.nan
            ds, dc, de = theirs.get(t, ("-", math.nan, math.nan))
            line = (f"| {t:.0e} | {setting} | {err:.3g} | {ratio:.3g} | {ds} | {de:.3g} | "
                    f"{dc / docs_base:.3g} |")
            for run in runs:
                rows = dict(run.get(scene, []))
                q, first = rows.get(t), rows.get(THRESHOLDS[0])
                line += (f" {plot_pareto.setting(q)} | {q['cost'] / first['cost']:.3g} |"
                         if q and first else " - | - |")
            print(line)


if __name__ == "__main__":
    main()
