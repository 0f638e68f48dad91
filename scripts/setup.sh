#!/usr/bin/env bash
# Installs the Debian packages massspring's build, tests, benchmarks and demo need.
# Idempotent: does nothing when everything is there; runs apt-get update only when something is
# missing. Uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake ccache      # compiler, build system, compiler cache
  libeigen3-dev                     # the library's one dependency
  nlohmann-json3-dev                # massspring::io: JSON scenes
  libpugixml-dev                    # massspring::io: FOSSSim XML scenes
  libcli11-dev                      # examples: command lines
  doctest-dev                       # tests
  libbenchmark-dev                  # benchmarks
  libsuitesparse-dev                # benchmarks: CHOLMOD compared (optional for the library)
  python3 python3-matplotlib        # rendering pictures of frames
  pybind11-dev python3-dev python3-numpy  # the Python module (python/)
  python3-pytest                    # the Python module's tests (tests/python/)
  clang libclang-rt-14-dev          # fuzzing (scripts/fuzz.sh): clang++ and libFuzzer
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update
$sudo apt-get install -y --no-install-recommends "${missing[@]}"
