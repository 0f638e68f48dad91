#!/usr/bin/env bash
# Regenerates docs/performance.md and docs/images/perf_*.png: builds the benchmarks in Release
# (build-perf/), runs bench_fast_mass_spring, bench_factorization and bench_scale (plus the
# 1000 x 1000 cloth with --million), keeps their raw output in out/perf/, then tabulates and plots.
#
#   scripts/performance.sh            # ~10-15 minutes on 2 cores
#   scripts/performance.sh --million  # also the 1000 x 1000 cloth (~5 minutes more, ~1.5 GiB)
set -euo pipefail
cd "$(dirname "$0")/.."
million=0
[ "${1:-}" = "--million" ] && million=1

scripts/setup.sh
cmake -S . -B build-perf -DCMAKE_BUILD_TYPE=Release -DMASSSPRING_BUILD_TESTS=OFF \
  -DMASSSPRING_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-perf -j2 --target bench_fast_mass_spring bench_factorization bench_scale

mkdir -p out/perf
build-perf/benchmarks/bench_fast_mass_spring 2>&1 | tee out/perf/bench_fast_mass_spring.txt
build-perf/benchmarks/bench_factorization | tee out/perf/factorization.md
build-perf/benchmarks/bench_scale | tee out/perf/scale.md
if [ "$million" = 1 ]; then
  /usr/bin/time -v build-perf/benchmarks/bench_scale --grid 1000 --frames 10 \
    > out/perf/million.md 2> out/perf/million_time.txt
  cat out/perf/million.md
fi
# Debian's python3 (with matplotlib), not a pyenv shim on PATH.
/usr/bin/python3 scripts/plot_performance.py out/perf
