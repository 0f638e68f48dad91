#!/usr/bin/env python3
"""scripts/demo.sh needs only what the demo uses: run by ctest (tests/CMakeLists.txt) as

    demo_packages.py SOURCE_DIR WORK_DIR

Checks that
- demo.sh installs with `scripts/setup.sh demo`, and that set (`scripts/setup.sh demo --print`)
  holds the compiler, CMake, the library's and massspring-simulate's dependencies and matplotlib,
  and none of the test, benchmark, Python-module or fuzzing tools (`scripts/setup.sh --print`,
  what scripts/test.sh installs, holds them all);
- demo.sh's own configure command (run as written, into WORK_DIR) succeeds when CMake cannot find
  any of those tools' packages (CMAKE_DISABLE_FIND_PACKAGE_*), and generates massspring_simulate.
Only the standard library."""

import os
import shlex
import shutil
import subprocess
import sys

DEMO = {"build-essential", "cmake", "libeigen3-dev", "nlohmann-json3-dev", "libpugixml-dev",
        "libcli11-dev", "python3", "python3-matplotlib", "zlib1g-dev", "libjs-three"}
NOT_FOR_THE_DEMO = {"doctest-dev", "libbenchmark-dev", "libsuitesparse-dev", "pybind11-dev",
                    "python3-dev", "python3-numpy", "python3-pytest", "clang",
                    "libclang-rt-14-dev", "chromium", "chromium-driver", "python3-selenium",
                    "python3-meshio"}
# the CMake packages of those tools
HIDDEN = ["doctest", "benchmark", "CHOLMOD", "pybind11", "Python", "Python3"]


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def commands(script):
    """The script's command lines, continuation lines joined, comments dropped."""
    out, line = [], ""
    with open(script) as handle:
        for raw in handle:
            text = raw.rstrip("\n")
            if not line and text.lstrip().startswith("#"):
                continue
            line += text[:-1] + " " if text.endswith("\\") else text
            if not text.endswith("\\"):
                if line.strip():
                    out.append(line.strip())
                line = ""
    return out


def main():
    if len(sys.argv) != 3:
        fail(__doc__)
    source, work = sys.argv[1:]
    demo_sh = os.path.join(source, "scripts", "demo.sh")
    setup = os.path.join(source, "scripts", "setup.sh")
    lines = commands(demo_sh)
    calls = [c for c in lines if c.startswith("scripts/setup.sh")]
    if calls != ["scripts/setup.sh demo"]:
        fail(f"demo.sh calls {calls}, expected exactly `scripts/setup.sh demo`")

    def listed(*args):
        result = subprocess.run([setup, *args, "--print"], capture_output=True, text=True)
        if result.returncode != 0:
            fail(f"setup.sh {' '.join(args)} --print: exit {result.returncode} {result.stderr}")
        return set(result.stdout.split())

    demo, everything = listed("demo"), listed()
    if not DEMO <= demo:
        fail(f"the demo's packages lack {sorted(DEMO - demo)}")
    if demo & NOT_FOR_THE_DEMO:
        fail(f"the demo installs test tools: {sorted(demo & NOT_FOR_THE_DEMO)}")
    if not (DEMO | NOT_FOR_THE_DEMO) <= everything:
        fail(f"setup.sh (everything) lacks {sorted((DEMO | NOT_FOR_THE_DEMO) - everything)}")

    configure = [c for c in lines if c.startswith("cmake -S")]
    if len(configure) != 1:
        fail(f"demo.sh configures {len(configure)} times, expected once: {configure}")
    argv = [a for a in shlex.split(configure[0].split(">")[0])]
    argv = [os.path.join(work, "build") if a == "$build" else a for a in argv]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    hidden = [f"-DCMAKE_DISABLE_FIND_PACKAGE_{p}=ON" for p in HIDDEN]
    result = subprocess.run(argv + hidden, cwd=source, capture_output=True, text=True)
    if result.returncode != 0:
        fail(f"demo.sh's configure without the test tools' packages failed:\n{result.stdout}"
             f"{result.stderr}")
    targets = subprocess.run(["cmake", "--build", os.path.join(work, "build"), "--target", "help"],
                             capture_output=True, text=True).stdout
    if "massspring_simulate" not in targets:
        fail("demo.sh's configure does not generate massspring_simulate")
    shutil.rmtree(work, ignore_errors=True)
    print(f"OK: the demo installs {len(demo)} packages (no test tools) and configures without "
          f"{', '.join(HIDDEN)}")


if __name__ == "__main__":
    main()
