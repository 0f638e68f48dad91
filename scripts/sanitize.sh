#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer: configures the asan-ubsan
# preset (CMakePresets.json: RelWithDebInfo, warnings are errors, no examples, tools, benchmarks
# or Python module), builds massspring_tests only and runs ctest without the soak and package
# labels (too slow under the sanitizers, and the package consumers are not built with them). Any
# report fails its test: UBSan is built with -fno-sanitize-recover=all, ASan halts on the first
# error, LSan reports leaks at exit.
# Usage: scripts/sanitize.sh [extra ctest arguments]
# Env: BUILD_DIR (default build-asan), MASSSPRING_SANITIZE (default address,undefined),
#      MASSSPRING_SHARED_DIR (default ../shared beside the checkout),
#      MASSSPRING_REQUIRE_SHARED=1 to fail when those scenes are missing (CI sets it).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/setup.sh

build=${BUILD_DIR:-build-asan}
sanitize=${MASSSPRING_SANITIZE:-address,undefined}
shared=${MASSSPRING_SHARED_DIR:-$root/../shared}
require=${MASSSPRING_REQUIRE_SHARED:-0}
jobs=$(nproc 2>/dev/null || echo 2)

cmake --preset asan-ubsan -B "$build" -DMASSSPRING_SANITIZE="$sanitize" \
  -DMASSSPRING_SHARED_DIR="$shared" \
  -DMASSSPRING_REQUIRE_SHARED="$([ "$require" = 1 ] && echo ON || echo OFF)"
cmake --build "$build" -j "$jobs" --target massspring_tests

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:halt_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$build" --output-on-failure -j "$jobs" -LE 'soak|package' "$@"
