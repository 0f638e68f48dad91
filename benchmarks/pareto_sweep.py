#!/usr/bin/python3
"""Writes benchmarks/pareto_sweep.json: benchmarks/pareto.cpp's run-time-against-error study as a
massspring.sweep spec (docs/sweeps.md), the same runs over the same scenes
(massspring.sweep.generators:pareto), plus two RK4 reference runs per scene.

    PYTHONPATH=build/python python3 benchmarks/pareto_sweep.py [--scenes chain,net,...] [--out F]
        [--min-time SECONDS]
    python3 -m massspring.sweep benchmarks/pareto_sweep.json --out out/pareto_sweep.h5
    python3 scripts/plot_pareto_sweep.py out/pareto_sweep.h5 out/pareto_sweep

Each run steps its scene to the end time T (1 s; the orbit 1.5 pi s) at dt = T / ceil(T / dt0),
as pareto.cpp does, with no energy guard (a run that does not stay finite is "diverged"; one whose
error exceeds 1 counts as diverged in the plot), a budget of 60 s projected from its first steps
(past it: "skipped"), and, as pareto.cpp, a run shorter than --min-time repeated until its loops
add up to it (the plot takes the fastest). The explicit methods run from 0.9 x their
stability_limit (at most 1/30 s) down by 6 halvings; the implicit ones at 1/30 ... 1/480 s:
BackwardEuler linearized and Newton, local-global at 1, 3, 10, 30 and 100 iterations, with
tolerances 1e-3 and 1e-6 (at most 1000 iterations) and with 10 Chebyshev iterations. The
reference is RK4 at the step reference_solution() settled on for each scene (docs/benchmarks.md)
and at half of it: the plot script measures errors against the finer and reports how far the two
differ."""

import argparse
import json
import math
import os
import sys

import massspring as ms
from massspring.sweep.generators import PARETO_END_TIMES, pareto

# reference_solution()'s RK4 steps for each scene (docs/benchmarks.md, "Scenes and references").
REFERENCE_DT = {"chain": 0.000101, "net": 5.96e-05, "orbit": 0.0046, "cloth32": 8.28e-05,
                "cloth64": 8.15e-05}
SCENES = ("chain", "net", "orbit", "cloth32", "cloth64")


def steps_for(end_time, dt):
    """pareto.cpp's run(): steps = max(1, ceil(T / dt - 1e-9)), then dt = T / steps."""
    steps = max(1, math.ceil(end_time / dt - 1e-9))
    return steps, end_time / steps


def runs_of(scene):
    system = pareto(scene)
    end = PARETO_END_TIMES[scene]
    generate = {"function": "massspring.sweep.generators:pareto", "arguments": {"scene": scene}}
    runs = []

    def add(family, setting, dt, **options):
        steps, dt = steps_for(end, dt)
        runs.append({"name": f"{scene}/{family}/{setting}", "generate": generate, "dt": dt,
                     "frames": steps, **options})

    def explicit(bound):
        h, out = min(0.9 * bound, 1.0 / 30), []
        for _ in range(6):
            out.append(h)
            h /= 2
        return out

    se = ms.stability_limit(system, ms.ExplicitMethod.SymplecticEuler)
    rk = ms.stability_limit(system, ms.ExplicitMethod.RK4)
    for dt in explicit(se):
        add("ForwardEuler", "-", dt, integrator="forward-euler")
        add("SymplecticEuler", "-", dt, integrator="symplectic-euler")
    for dt in explicit(rk):
        add("RK4", "-", dt, integrator="rk4")
    for j in range(5):
        dt = 1.0 / (30 << j)
        add("BackwardEuler", "linearized", dt, integrator="linearized-backward-euler")
        add("BackwardEuler", "newton", dt, integrator="backward-euler")
        for it in (1, 3, 10, 30, 100):
            add("LocalGlobal", f"it={it}", dt, integrator="fast-mass-spring", iterations=it)
        for tol, text in ((1e-3, "0.001"), (1e-6, "1e-06")):
            add("LocalGlobal", f"tol={text}", dt, integrator="fast-mass-spring",
                iterations=1000, tolerance=tol)
        add("LocalGlobal", "chebyshev it=10", dt, integrator="fast-mass-spring", iterations=10,
            acceleration="chebyshev")
    for factor, setting in ((1, "reference"), (2, "reference/2")):
        steps, dt = steps_for(end, REFERENCE_DT[scene] / factor)
        runs.append({"name": f"{scene}/Reference/{setting}", "generate": generate, "dt": dt,
                     "frames": steps, "integrator": "rk4", "save_frames": "ends"})
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", default=",".join(SCENES))
    parser.add_argument("--min-time", type=float, default=0.2,
                        help="repeat each run shorter than this [s] (timed only) until its loops "
                             "add up to it, as pareto.cpp's --min-time (default 0.2); 0: once")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__),
                                                      "pareto_sweep.json"))
    args = parser.parse_args()
    scenes = args.scenes.split(",")
    for s in scenes:
        if s not in SCENES:
            sys.exit(f"pareto_sweep: unknown scene {s!r} (expected {', '.join(SCENES)})")
    runs = [r for s in scenes for r in runs_of(s)]
    spec = {
        "description": "benchmarks/pareto.cpp's study (written by benchmarks/pareto_sweep.py)",
        "base": {"guard_growth": 0, "budget": 60, "energy": True, "min_time": args.min_time},
        "runs": runs,
    }
    with open(args.out, "w") as handle:
        json.dump(spec, handle, indent=1)
        handle.write("\n")
    print(f"{args.out}: {len(runs)} runs over {', '.join(scenes)}")


if __name__ == "__main__":
    main()
