#!/usr/bin/python3
"""The Python module's overhead: a Python loop of FastMassSpring.step() on the flag scene against
the same loop in C++ (massspring-simulate, which times each solver.step() with steady_clock).

    PYTHONPATH=build/python python3 benchmarks/python_overhead.py \
        [--simulate build/tools/massspring-simulate] [--scene examples/scenes/flag.json] \
        [--frames 150] [--rounds 6]

Each round runs both, alternating which goes first: the C++ loop (--guard-growth 0, so that it
times the plain step, as Python does) and, in this process, the same scene, gravity (0, -9.8, 0),
solver options (the defaults: 50 iterations) and dt (1/30 s) stepped from Python, each step timed
with time.perf_counter() around `solver.step(system)`. Per round: the median and the mean
milliseconds per step of each, and the ratio Python / C++. Printed at the end: the median over the
rounds of each ratio (the number to quote; <= 1.05 is the module's target) and the whole Python
loop's time per step (loop and timer included) against the C++ mean.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import time

import massspring as ms

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def cpp(simulate, scene, frames):
    """(median, mean) ms per step, as massspring-simulate measures them."""
    out = subprocess.run([simulate, scene, "--frames", str(frames), "--guard-growth", "0"],
                         capture_output=True, text=True, check=True).stdout
    m = re.search(r"median ([0-9.]+) ms per step \(mean ([0-9.]+)", out)
    if not m:
        sys.exit(f"unexpected output of {simulate}:\n{out}")
    return float(m.group(1)), float(m.group(2))


def python(scene, frames):
    """(median, mean, whole loop) ms per step from Python."""
    system = ms.load_scene(scene)
    system.add_force(ms.Gravity([0, -9.8, 0]))
    solver = ms.FastMassSpring()
    solver.precompute(system, 1.0 / 30)
    ms_per_step = []
    clock = time.perf_counter
    loop_start = clock()
    for _ in range(frames):
        start = clock()
        report = solver.step(system)
        ms_per_step.append(1000 * (clock() - start))
        if not report.ok():
            sys.exit(f"a step failed: {report}")
    loop = 1000 * (clock() - loop_start) / frames
    return statistics.median(ms_per_step), statistics.fmean(ms_per_step), loop


def main():
    p = argparse.ArgumentParser(description="Python loop of step() against the C++ loop.")
    p.add_argument("--simulate", default=os.path.join(ROOT, "build", "tools",
                                                       "massspring-simulate"))
    p.add_argument("--scene", default=os.path.join(ROOT, "examples", "scenes", "flag.json"))
    p.add_argument("--frames", type=int, default=150)
    p.add_argument("--rounds", type=int, default=6)
    args = p.parse_args()

    median_ratios, mean_ratios, loop_ratios = [], [], []
    print(f"{args.scene}, {args.frames} steps per run, FastMassSpring defaults, dt 1/30 s")
    print("round  C++ median  C++ mean   Py median   Py mean   Py loop   ratio median  ratio mean")
    for r in range(args.rounds):
        if r % 2 == 0:
            c = cpp(args.simulate, args.scene, args.frames)
            py = python(args.scene, args.frames)
        else:
            py = python(args.scene, args.frames)
            c = cpp(args.simulate, args.scene, args.frames)
        median_ratios.append(py[0] / c[0])
        mean_ratios.append(py[1] / c[1])
        loop_ratios.append(py[2] / c[1])
        print(f"{r:5d} {c[0]:10.3f} {c[1]:10.3f} {py[0]:10.3f} {py[1]:10.3f} {py[2]:9.3f}"
              f" {median_ratios[-1]:13.4f} {mean_ratios[-1]:11.4f}")
    print(f"Python / C++, median over {args.rounds} rounds: per-step median "
          f"{statistics.median(median_ratios):.4f}, per-step mean "
          f"{statistics.median(mean_ratios):.4f}, whole Python loop / C++ mean "
          f"{statistics.median(loop_ratios):.4f}")


if __name__ == "__main__":
    main()
