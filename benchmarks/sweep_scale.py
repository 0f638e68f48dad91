#!/usr/bin/python3
"""The speed-up of massspring.sweep with 2 Dask workers over 1 (docs/sweeps.md, "Scale").

    PYTHONPATH=build/python python3 benchmarks/sweep_scale.py [--runs 16] [--rounds 3]
        [--scene cloth:40x30] [--frames 600] [--workers 1,2] [--equal]

Each round times the same sweep of RUNS runs (SCENE, local-global with 1 to RUNS iterations so
that every run is its own, FRAMES frames) into a fresh file, on a local cluster of each worker
count in turn (one thread per worker process). The time is the sweep's own: from the first
submission to the last result committed; the cluster is started before the clock and its start
is not counted. Prints each round's times and the median speed-up of each count over the first."""

import argparse
import json
import os
import statistics
import tempfile
import time

from dask.distributed import Client, LocalCluster

from massspring.sweep import sweep


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=16)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--scene", default="cloth:40x30")
    parser.add_argument("--frames", type=int, default=600)
    parser.add_argument("--workers", default="1,2")
    parser.add_argument("--equal", action="store_true",
                        help="runs of equal work (12 iterations, stiffness scaled by 1.00, "
                             "1.01, ...) instead of 5 to RUNS + 4 iterations")
    args = parser.parse_args()
    counts = [int(w) for w in args.workers.split(",")]
    times = {w: [] for w in counts}
    with tempfile.TemporaryDirectory() as folder:
        spec = os.path.join(folder, "spec.json")
        with open(spec, "w") as handle:
            if args.equal:  # the same work in every run: 12 iterations, stiffness x 1.00 ...
                grid = {"stiffness_scale": [1 + 0.01 * k for k in range(args.runs)]}
                base = {"generate": args.scene, "frames": args.frames, "iterations": 12}
            else:
                grid = {"iterations": list(range(5, 5 + args.runs))}
                base = {"generate": args.scene, "frames": args.frames}
            json.dump({"base": base, "grid": grid}, handle)
        for r in range(args.rounds):
            for w in counts:
                with LocalCluster(n_workers=w, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, Client(cluster) as client:
                    client.run(lambda: __import__("massspring"))  # imported before the clock
                    out = os.path.join(folder, f"round{r}-{w}.h5")
                    start = time.perf_counter()
                    summary = sweep(spec, out, client=client, progress=False)
                    seconds = time.perf_counter() - start
                assert summary["ok"] == args.runs, summary
                times[w].append(seconds)
                print(f"round {r + 1}: {w} worker{'s' if w > 1 else ''}: {seconds:.2f} s",
                      flush=True)
    first = counts[0]
    for w in counts[1:]:
        ratios = [a / b for a, b in zip(times[first], times[w])]
        print(f"{args.runs} runs: {w} workers over {first}: median speed-up "
              f"{statistics.median(ratios):.2f} (rounds: {', '.join(f'{x:.2f}' for x in ratios)}); "
              f"median times {statistics.median(times[first]):.2f} s and "
              f"{statistics.median(times[w]):.2f} s")


if __name__ == "__main__":
    main()
