"""`pip install .` (docs/python.md): the package `massspring`, its compiled module built by the
project's own CMake (python/CMakeLists.txt, target massspring_python) and its pure-Python parts.

    python3 -m venv --system-site-packages ENV         # sees Debian's numpy, setuptools, wheel
    ENV/bin/pip install -v --no-build-isolation .      # nothing downloaded; -v: CMake's progress

Without --no-build-isolation pip installs setuptools and wheel from the package index into a
build environment of its own first, which fails offline. Without -v pip shows only "still
running..." while the module compiles (minutes without a compiler cache).

build_ext configures CMake in MASSSPRING_PIP_BUILD_DIR (default: build-pip in the checkout, kept
between installs so a second one rebuilds nothing) with the Release build's options, builds only
the module, with the module laid out in setuptools' build folder. Its compile commands are the
Release build's (same flags, same paths relative to the checkout and the build folder), so the
compiler cache (CMakeLists.txt: ccache with base_dir the checkout) serves a module the build
already compiled. Environment:

    MASSSPRING_PIP_BUILD_DIR   CMake's build folder (default <checkout>/build-pip)
    MASSSPRING_CMAKE_ARGS      more CMake arguments, split on spaces (e.g. -DMASSSPRING_WERROR=ON,
                               as scripts/test.sh builds, to share its cache entries)
    MASSSPRING_BUILD_JOBS      parallel compile jobs (default: the machine's cores)
    CMAKE                      the cmake program (default: cmake on PATH)
"""

import os
import re
import shlex
import subprocess
import sys
import time

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(ROOT, "include", "massspring", "version.hpp")) as handle:
        text = handle.read()
    parts = [re.search(rf"#define MASSSPRING_VERSION_{p} (\d+)", text).group(1)
             for p in ("MAJOR", "MINOR", "PATCH")]
    return ".".join(parts)


class CMakeExtension(Extension):
    """An extension CMake builds: no sources for setuptools to compile."""

    def __init__(self, name, target):
        super().__init__(name, sources=[])
        self.target = target


class CMakeBuild(build_ext):
    """Builds each CMakeExtension with the project's CMakeLists.txt."""

    def build_extension(self, ext):
        if not isinstance(ext, CMakeExtension):
            super().build_extension(ext)
            return
        cmake = os.environ.get("CMAKE", "cmake")
        build_dir = os.path.abspath(os.environ.get("MASSSPRING_PIP_BUILD_DIR",
                                                   os.path.join(ROOT, "build-pip")))
        # where setuptools expects massspring/_core<suffix>: the package folder's parent
        target = os.path.abspath(self.get_ext_fullpath(ext.name))
        package_root = os.path.dirname(os.path.dirname(target))
        configure = [
            cmake, "-S", ROOT, "-B", build_dir,
            "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython_EXECUTABLE={sys.executable}",
            "-DMASSSPRING_BUILD_PYTHON=ON",
            "-DMASSSPRING_BUILD_TESTS=OFF",
            "-DMASSSPRING_BUILD_EXAMPLES=OFF",
            "-DMASSSPRING_BUILD_BENCHMARKS=OFF",
            "-DMASSSPRING_INSTALL=OFF",
            f"-DMASSSPRING_PYTHON_OUTPUT_DIR={package_root}",
        ] + shlex.split(os.environ.get("MASSSPRING_CMAKE_ARGS", ""))
        jobs = os.environ.get("MASSSPRING_BUILD_JOBS", str(os.cpu_count() or 1))
        build = [cmake, "--build", build_dir, "--target", ext.target, "-j", jobs]
        print(f"massspring: CMake builds the target {ext.target} only (no tests, examples, "
              f"benchmarks or tools) in {build_dir}, {jobs} jobs: about 5 minutes of one core "
              "when it compiles every file, seconds when ccache holds them", flush=True)
        started = time.monotonic()
        for command in (configure, build):
            print(" ".join(shlex.quote(c) for c in command), flush=True)
            subprocess.run(command, check=True)
        print(f"massspring: {ext.target} built in {time.monotonic() - started:.0f} s", flush=True)
        built = os.path.join(package_root, *ext.name.split(".")[:-1])
        suffix = os.path.basename(target)
        if not os.path.exists(os.path.join(built, suffix)):
            raise RuntimeError(f"CMake built no {suffix} in {built} (is the target's "
                               "OUTPUT_NAME the extension's last name?)")


setup(
    name="massspring",
    version=version(),
    description="Header-only C++17 mass-spring simulation on Eigen: the Python module and "
                "parameter sweeps on Dask",
    license="see LICENSE",
    packages=["massspring", "massspring.sweep"],
    package_dir={"": "python"},
    ext_modules=[CMakeExtension("massspring._core", target="massspring_python")],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.9",
    install_requires=["numpy"],
    extras_require={"sweep": ["dask", "distributed", "h5py"]},
    zip_safe=False,
)
