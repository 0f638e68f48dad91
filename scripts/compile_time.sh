#!/usr/bin/env bash
# Compile time of a consumer translation unit that instantiates FastMassSpring (precompute + step,
# benchmarks/compile_time/consumer.cpp) against Eigen's own SimplicialLLT on an n x 3 right-hand
# side (eigen_llt.cpp): both at -O2 with the same compiler, best of `runs` (default 2), in CPU
# seconds of the compiler (user + system), which other processes on the machine move much less
# than the wall clock. Prints both and their ratio, then the same consumer compiled with
# MASSSPRING_EXTERN_TEMPLATES (the solver instantiated once elsewhere, by instances.hpp; see
# docs/fast_mass_spring.md, "Compile time") and what that one instantiating unit costs.
# Usage: scripts/compile_time.sh [runs]     Env: CXX (default g++), EIGEN_INCLUDE.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-2}
cxx=${CXX:-g++}
eigen=${EIGEN_INCLUDE:-/usr/include/eigen3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

best() {  # least CPU time in seconds of compiling $1 (extra flags after it), over $runs runs
  local source=$1
  shift
  python3 - "$runs" "$cxx" -std=c++17 -O2 -I"$root/include" -I"$eigen" "$@" -c "$source" -o "$out/a.o" <<'PY'
import resource, subprocess, sys
runs, command = int(sys.argv[1]), sys.argv[2:]
best = None
for _ in range(runs):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    best = cpu if best is None else min(best, cpu)
print(f"{best:.2f}")
PY
}

consumer=$(best "$root/benchmarks/compile_time/consumer.cpp")
eigen_s=$(best "$root/benchmarks/compile_time/eigen_llt.cpp")
extern_s=$(best "$root/benchmarks/compile_time/consumer.cpp" -DMASSSPRING_EXTERN_TEMPLATES)
printf '#include <massspring/integrators/local_global/instances.hpp>\n' >"$out/instances.cpp"
instances=$(best "$out/instances.cpp")
ratio=$(python3 -c "print($consumer / $eigen_s)")
extern_ratio=$(python3 -c "print($extern_s / $eigen_s)")
echo "compiler: $("$cxx" --version | head -1); -O2; best of $runs, CPU seconds"
echo "FastMassSpring consumer (precompute + step): $consumer s"
echo "Eigen SimplicialLLT, n x 3 right-hand side:  $eigen_s s"
printf 'ratio: %.2f\n' "$ratio"
echo "the consumer with MASSSPRING_EXTERN_TEMPLATES:  $extern_s s (ratio $(printf '%.2f' "$extern_ratio"))"
echo "instances.hpp, the one unit that instantiates (4 systems): $instances s"
