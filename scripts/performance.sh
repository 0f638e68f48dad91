#!/usr/bin/env bash
# Regenerates the tables of docs/performance.md (between its "generated" markers) and
# docs/images/perf_*.png: builds the benchmarks in Release (build-perf/), runs bench_step,
# bench_options, bench_acceleration, bench_threads, bench_factorization and bench_scale (plus the
# 1000 x 1000 cloth with --million), keeps their JSON output and a description of the machine
# (lscpu, compiler, load average, date) in out/perf/, then tabulates and plots.
#
#   scripts/performance.sh            # ~15-20 minutes on 2 cores, plus the build
#   scripts/performance.sh --million  # also the 1000 x 1000 cloth (~2 minutes more, ~2.5 GiB)
set -euo pipefail
cd "$(dirname "$0")/.."
million=0
[ "${1:-}" = "--million" ] && million=1

scripts/setup.sh
cmake -S . -B build-perf -DCMAKE_BUILD_TYPE=Release -DMASSSPRING_BUILD_TESTS=OFF \
  -DMASSSPRING_BUILD_EXAMPLES=OFF >/dev/null
programs=(bench_step bench_options bench_acceleration bench_threads bench_factorization)
cmake --build build-perf -j2 --target massspring_performance_programs  # all of them, two at a time

out=out/perf
mkdir -p "$out"
rm -f "$out"/*.json
# The machine, from the run: lscpu, the compiler and its flags, Eigen's version, the date and the
# load average before (and, below, after) the benchmarks.
cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' build-perf/CMakeCache.txt)
flags=$(sed -n 's/^CMAKE_CXX_FLAGS_RELEASE:[A-Z]*=//p' build-perf/CMakeCache.txt)
eigen_dir=$(sed -n 's/^Eigen3_DIR:[A-Z]*=//p' build-perf/CMakeCache.txt)
eigen=$(sed -n 's/^set(PACKAGE_VERSION "\(.*\)")/\1/p' "$eigen_dir/Eigen3ConfigVersion.cmake" 2>/dev/null || true)
/usr/bin/python3 - "$out/machine.json" "$cxx" "$flags" "$eigen" <<'EOF'
import datetime, json, os, subprocess, sys
path, cxx, flags, eigen = sys.argv[1:5]
machine = {
    "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
    "compiler": subprocess.run([cxx, "--version"], capture_output=True, text=True,
                               check=True).stdout.splitlines()[0], "flags": flags, "eigen": eigen, "nproc": os.cpu_count(),
    "load_start": open("/proc/loadavg").read().split()[:3],
    "lscpu": json.loads(subprocess.run(["lscpu", "--json"], capture_output=True, text=True,
                                       check=True).stdout)["lscpu"],
}
json.dump(machine, open(path, "w"), indent=1)
EOF

for p in "${programs[@]}"; do
  build-perf/benchmarks/"$p" --benchmark_out="$out/${p#bench_}.json" --benchmark_out_format=json
done
build-perf/benchmarks/bench_scale --out "$out/scale.json"
if [ "$million" = 1 ]; then
  build-perf/benchmarks/bench_scale --grid 1000 --frames 10 --out "$out/million.json"
fi
/usr/bin/python3 - "$out/machine.json" <<'EOF'
import json, sys
machine = json.load(open(sys.argv[1]))
machine["load_end"] = open("/proc/loadavg").read().split()[:3]
json.dump(machine, open(sys.argv[1], "w"), indent=1)
EOF
# Debian's python3 (with matplotlib), not a pyenv shim on PATH.
/usr/bin/python3 scripts/plot_performance.py "$out"
