#!/usr/bin/env bash
# Stability stress suite (benchmarks/stability.cpp): builds it in Release (build-stab/), runs every
# integrator over stiffness 1e0..1e8 N/m x dt 1e-4..1/30 s on a chain and an 8 x 8 cloth, keeps the
# CSV output in out/stability/, then regenerates docs/stability.md and docs/images/stability_*.png.
#
#   scripts/stability.sh          # the full suite: ~10-15 minutes on one core
#   scripts/stability.sh --quick  # smoke test (k = 1e0 and 1e8 N/m, 1 simulated second) into
#                                 # out/stability-quick/; leaves docs/ alone
#
# Progress (done/total, elapsed, ETA) goes to stderr. The exit code is the driver's: 1 when some
# explicit run at or below stable_time_step() was not stable (the docs are written all the same).
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
[ "${1:-}" = "--quick" ] && quick=1

scripts/setup.sh
cmake -S . -B build-stab -DCMAKE_BUILD_TYPE=Release -DMASSSPRING_WERROR=ON \
  -DMASSSPRING_BUILD_BENCHMARKS=ON >/dev/null
cmake --build build-stab -j1 --target stability

if [ "$quick" = 1 ]; then
  exec build-stab/benchmarks/stability --quick --out out/stability-quick
fi

mkdir -p out/stability
# Where it ran, for the page: the CPU and the load other jobs put on the machine.
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
echo "$(nproc) cores of ${cpu:-an unknown CPU}, load average at the start $(cut -d' ' -f1-3 /proc/loadavg)" \
  > out/stability/machine.txt
status=0
build-stab/benchmarks/stability --out out/stability || status=$?
if [ "$status" -gt 1 ]; then
  echo "stability: the driver failed (exit $status)" >&2
  exit "$status"
fi
# Debian's python3 (with matplotlib), not a pyenv shim on PATH.
/usr/bin/python3 scripts/plot_stability.py out/stability
if [ "$status" = 1 ]; then
  echo "stability: some explicit run at or below stable_time_step() was not stable; see docs/stability.md" >&2
fi
exit "$status"
