#!/usr/bin/env bash
# Installs the Debian packages massspring needs: `scripts/setup.sh` everything the build, tests,
# benchmarks, fuzzing and demo use (scripts/test.sh); `scripts/setup.sh demo` only what
# scripts/demo.sh uses (compiler, CMake, the library's and massspring-simulate's dependencies,
# matplotlib, three.js for the demo's page); `scripts/setup.sh pareto` only what scripts/pareto.sh
# uses (compiler, CMake, Eigen, Google Benchmark, matplotlib); `--print` lists the packages of the
# set instead of installing them.
# Idempotent: does nothing when everything is there; runs apt-get update only when something is
# missing. Uses sudo when not root.
set -euo pipefail

demo=(
  build-essential cmake ccache      # compiler, build system, compiler cache
  libeigen3-dev                     # the library's one dependency
  nlohmann-json3-dev                # massspring::io: JSON scenes
  libpugixml-dev                    # massspring::io: FOSSSim XML scenes
  libcli11-dev                      # tools: command lines
  python3 python3-matplotlib        # rendering pictures of frames
  zlib1g-dev libjs-three            # massspring-simulate --html: deflated positions, three.js
)
pareto=(
  build-essential cmake ccache      # compiler, build system, compiler cache
  libeigen3-dev                     # the library's one dependency
  libbenchmark-dev                  # benchmarks/CMakeLists.txt needs it (pareto itself does not)
  python3 python3-matplotlib        # scripts/plot_pareto.py
)
more=(
  doctest-dev                       # tests
  libbenchmark-dev                  # benchmarks
  libsuitesparse-dev                # benchmarks: CHOLMOD compared (optional for the library)
  libbullet-dev                     # benchmarks: the drape against Bullet's soft body (optional)
  pybind11-dev python3-dev python3-numpy  # the Python module (python/)
  python3-pytest                    # the Python module's tests (tests/python/)
  python3-dask python3-distributed python3-h5py  # massspring.sweep (docs/sweeps.md)
  python3-venv python3-pip python3-setuptools python3-wheel  # `pip install .` (setup.py)
  clang libclang-rt-14-dev          # fuzzing (scripts/fuzz.sh): clang++ and libFuzzer
  chromium chromium-driver          # the --html pages tested in a real browser (headless)
  python3-selenium python3-pil      #   driven by Selenium; screenshots read with Pillow
  python3-meshio                    # the --vtk frames read back by an independent reader
)

set_name=all
print=0
for arg in "$@"; do
  case "$arg" in
    demo | pareto | all) set_name=$arg ;;
    --print) print=1 ;;
    *)
      echo "setup: unknown argument \"$arg\" (expected demo, pareto, all or --print)" >&2
      exit 1
      ;;
  esac
done
case "$set_name" in
  demo) packages=("${demo[@]}") ;;
  pareto) packages=("${pareto[@]}") ;;
  *) packages=("${demo[@]}" "${more[@]}") ;;
esac
if [ "$print" = 1 ]; then
  printf '%s\n' "${packages[@]}"
  exit 0
fi

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
