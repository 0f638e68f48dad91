#!/usr/bin/env bash
# Set-up, configure, build (tests, examples, tools, benchmarks; -Werror), run every test.
# Every test includes the long soak tests (label soak, a few minutes; `scripts/test.sh -LE soak`
# leaves them out). Sanitizers: scripts/sanitize.sh.
# Usage: scripts/test.sh [extra ctest arguments]
# Env: BUILD_DIR (default build), MASSSPRING_SHARED_DIR (default ../shared beside the checkout),
#      MASSSPRING_REQUIRE_SHARED=1 to fail when those scenes are missing (CI sets it).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/setup.sh

build=${BUILD_DIR:-build}
shared=${MASSSPRING_SHARED_DIR:-$root/../shared}
require=${MASSSPRING_REQUIRE_SHARED:-0}
jobs=$(nproc 2>/dev/null || echo 2)

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DMASSSPRING_WERROR=ON \
  -DMASSSPRING_SHARED_DIR="$shared" \
  -DMASSSPRING_REQUIRE_SHARED="$([ "$require" = 1 ] && echo ON || echo OFF)"
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure -j "$jobs" "$@"
