#!/usr/bin/env bash
# Regenerates the run-time-against-error part of docs/benchmarks.md and docs/images/pareto_*.png:
# builds benchmarks/pareto in Release (build-perf/), runs it (RK4 references cached in
# out/reference/, points in out/pareto/), then tabulates and plots.
#
#   scripts/pareto.sh                  # ~25 minutes on 2 cores the first time (references
#                                      # included), less once out/reference/ holds them
#   scripts/pareto.sh --budget 30      # extra arguments go to the pareto program
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake -S . -B build-perf -DCMAKE_BUILD_TYPE=Release -DMASSSPRING_BUILD_TESTS=OFF \
  -DMASSSPRING_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-perf -j2 --target pareto

build-perf/benchmarks/pareto --out out/pareto --cache out/reference "$@"
# Debian's python3 (with matplotlib), not a pyenv shim on PATH.
/usr/bin/python3 scripts/plot_pareto.py out/pareto docs
