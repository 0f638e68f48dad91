#!/usr/bin/env bash
# Run time against error (docs/benchmarks.md): builds benchmarks/pareto in Release (build-perf/),
# runs it (RK4 references cached in out/reference/), then tabulates and plots.
#
#   scripts/pareto.sh                  # the full benchmark, into out/pareto/: pareto.csv,
#                                      # references.csv, liu_table.csv, benchmarks.md (the tables)
#                                      # and images/pareto_*.png
#   scripts/pareto.sh --out DIR        # the same into DIR
#   scripts/pareto.sh --update-docs    # also rewrites docs/benchmarks.md's tables and
#                                      # docs/images/pareto_*.png (a full run only: refused with
#                                      # --quick or --scenes, whose tables would be partial)
#   scripts/pareto.sh --dry-run ...    # prints the commands it would run, runs none
#   scripts/pareto.sh --quick --scenes chain,net   # other arguments go to the pareto program
#
# The full run is long (it prints its progress and the time left as it goes; --quick is a short
# check). Installs only what it uses (scripts/setup.sh pareto: compiler, CMake, Eigen, Google
# Benchmark, matplotlib); the build leaves out the tests, examples, scene files and Python module.
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/pareto
update_docs=0
dry_run=0
partial=""
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out)
      [ $# -ge 2 ] || { echo "pareto.sh: --out needs a folder" >&2; exit 2; }
      out=$2
      shift 2
      ;;
    --update-docs) update_docs=1; shift ;;
    --dry-run) dry_run=1; shift ;;
    --quick | --scenes)
      partial=${partial:-$1}
      args+=("$1")
      shift
      ;;
    *) args+=("$1"); shift ;;
  esac
done
if [ "$update_docs" = 1 ] && [ -n "$partial" ]; then
  echo "pareto.sh: --update-docs needs the full benchmark; $partial would leave tables out of" \
    "docs/benchmarks.md (run without --update-docs: the results go to $out/)" >&2
  exit 2
fi

run() {
  if [ "$dry_run" = 1 ]; then
    printf '%q ' "$@"
    echo
  else
    "$@"
  fi
}

run scripts/setup.sh pareto
run cmake -S . -B build-perf -DCMAKE_BUILD_TYPE=Release -DMASSSPRING_BUILD_TESTS=OFF \
  -DMASSSPRING_BUILD_EXAMPLES=OFF -DMASSSPRING_BUILD_PYTHON=OFF -DMASSSPRING_WITH_IO=OFF \
  -DMASSSPRING_BUILD_BENCHMARKS=ON
run cmake --build build-perf -j2 --target pareto
run build-perf/benchmarks/pareto --out "$out" --cache out/reference ${args[@]+"${args[@]}"}
# Debian's python3 (with matplotlib), not a pyenv shim on PATH: the tables and plots into $out/
run /usr/bin/python3 scripts/plot_pareto.py "$out" "$out"
if [ "$update_docs" = 1 ]; then
  run /usr/bin/python3 scripts/plot_pareto.py "$out" docs
fi
