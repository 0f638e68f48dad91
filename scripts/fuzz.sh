#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang++ in build-fuzz and runs each for SECONDS
# (default 600), one after the other, printing libFuzzer's final statistics (executions, exec/s,
# coverage). Usage: scripts/fuzz.sh [seconds] [target...]
#   targets: fuzz_json_scene fuzz_fosssim_scene (default: both)
# Seeds come from the project's own scenes (examples/scenes, examples/scenes_xml) and the crash
# regressions in tests/data/fuzz; ../shared/scenes, when present, is read as an extra read-only
# corpus. New corpus entries go to build-fuzz/corpus/<target>; a crash is written to
# build-fuzz/artifacts/<target>/ and makes the script exit non-zero.
# FUZZ_NICE=1 runs the fuzzers under nice -n 19; FUZZ_JOBS sets the build's -j (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_json_scene fuzz_fosssim_scene)

scripts/setup.sh >/dev/null   # clang and libFuzzer among the rest (installs only what is missing)
command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (scripts/setup.sh installs clang)" >&2; exit 1; }
build=build-fuzz
CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMASSSPRING_BUILD_FUZZERS=ON \
  -DMASSSPRING_BUILD_TESTS=OFF -DMASSSPRING_BUILD_EXAMPLES=OFF -DMASSSPRING_BUILD_BENCHMARKS=OFF \
  -DMASSSPRING_INSTALL=OFF >/dev/null
cmake --build "$build" -j "${FUZZ_JOBS:-2}" --target "${targets[@]}"

nice_cmd=()
[ "${FUZZ_NICE:-0}" = 1 ] && nice_cmd=(nice -n 19)

# A JSON target input: the JSON scene, a NUL byte, then the OBJ file it names.
json_input() {
  local json=$1 obj
  obj=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["obj"])' "$json") || return 0
  [ -f "$(dirname "$json")/$obj" ] || return 0
  { cat "$json"; printf '\0'; cat "$(dirname "$json")/$obj"; }
}

status=0
for target in "${targets[@]}"; do
  corpus=$build/corpus/$target      # grows; libFuzzer writes new inputs to the first folder only
  seeds=$build/seeds/$target        # rebuilt each run from the project's scenes
  shared=$build/shared/$target      # read-only extra corpus from ../shared (never in the project)
  artifacts=$build/artifacts/$target
  rm -rf "$seeds" "$shared"
  mkdir -p "$corpus" "$seeds" "$shared" "$artifacts"
  case $target in
    fuzz_json_scene)
      for json in examples/scenes/*.json; do json_input "$json" >"$seeds/$(basename "$json")"; done
      if [ -d ../shared/scenes/jacobson ]; then
        for json in ../shared/scenes/jacobson/*.json; do
          json_input "$json" >"$shared/$(basename "$json")"
        done
      fi
      max_len=65536 ;;
    fuzz_fosssim_scene)
      cp examples/scenes_xml/*.xml "$seeds/"
      [ -d ../shared/scenes/fosssim ] && find ../shared/scenes/fosssim -name '*.xml' \
        -exec sh -c 'for f; do cp "$f" "$0/$(echo "${f#../shared/scenes/fosssim/}" | tr / _)"; done' "$shared" {} +
      max_len=16384 ;;
    *) echo "fuzz: unknown target $target" >&2; exit 1 ;;
  esac
  if [ -d "tests/data/fuzz/$target" ]; then cp tests/data/fuzz/"$target"/* "$seeds/" 2>/dev/null || true; fi
  echo "== $target: ${seconds} s"
  set +e
  "${nice_cmd[@]}" "$build/fuzz/$target" "$corpus" "$seeds" "$shared" \
    -max_total_time="$seconds" -print_final_stats=1 -max_len=$max_len -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$artifacts/" 2>&1 | tee "$build/$target.log" \
    | grep -E '^(#[0-9]+[[:space:]]+(INITED|DONE)|stat::|==[0-9]+==ERROR|SUMMARY|.*runtime error|artifact_prefix|Test unit written)'
  rc=${PIPESTATUS[0]}
  set -e
  if [ "$rc" -ne 0 ]; then
    echo "fuzz: $target FAILED (exit $rc): see $build/$target.log and $artifacts/" >&2
    status=1
  fi
done
exit $status
