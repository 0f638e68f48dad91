#!/usr/bin/env bash
# Regenerates the accuracy studies in docs/: run time against error (docs/benchmarks.md,
# docs/images/pareto_*.png; scripts/pareto.sh --update-docs) and the stability stress suite
# (docs/stability.md, docs/images/stability_*.png; scripts/stability.sh). The RK4 references are
# cached in out/reference/, computed the first time.
#
#   scripts/accuracy.sh
#
# Progress (done/total, elapsed, ETA) goes to stderr. Exits non-zero when either part fails
# (stability.sh: some explicit run at or below stable_time_step() was not stable).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/pareto.sh --update-docs
scripts/stability.sh
