#!/usr/bin/env bash
# Compile time of a consumer translation unit that instantiates FastMassSpring (precompute + step,
# benchmarks/compile_time/consumer.cpp) against Eigen's own SimplicialLLT on an n x 3 right-hand
# side (eigen_llt.cpp): both at -O2 with the same compiler, best of `runs` (default 2) wall times.
# Prints both and their ratio. Run it on an idle machine: the figure is a wall time.
# Usage: scripts/compile_time.sh [runs]     Env: CXX (default g++), EIGEN_INCLUDE.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-2}
cxx=${CXX:-g++}
eigen=${EIGEN_INCLUDE:-/usr/include/eigen3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

best() {  # best wall time in seconds of compiling $1, over $runs runs
  local source=$1 best_s="" start end s
  for _ in $(seq "$runs"); do
    start=$(date +%s.%N)
    "$cxx" -std=c++17 -O2 -I"$root/include" -I"$eigen" -c "$source" -o "$out/a.o"
    end=$(date +%s.%N)
    s=$(python3 -c "print($end - $start)")
    if [ -z "$best_s" ] || python3 -c "import sys; sys.exit(not $s < $best_s)"; then best_s=$s; fi
  done
  printf '%.2f' "$best_s"
}

consumer=$(best "$root/benchmarks/compile_time/consumer.cpp")
eigen_s=$(best "$root/benchmarks/compile_time/eigen_llt.cpp")
ratio=$(python3 -c "print($consumer / $eigen_s)")
echo "compiler: $("$cxx" --version | head -1); -O2; best of $runs"
echo "FastMassSpring consumer (precompute + step): $consumer s"
echo "Eigen SimplicialLLT, n x 3 right-hand side:  $eigen_s s"
printf 'ratio: %.2f (target <= 2)\n' "$ratio"
