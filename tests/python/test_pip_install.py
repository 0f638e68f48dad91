"""`pip install .` from the checkout, in a fresh virtual environment that sees Debian's packages
(python3 -m venv --system-site-packages), with Debian's setuptools and no build isolation and no
index (nothing downloaded): the package `massspring` is installed, compiled module and pure-Python
parts, and imports from outside the checkout without PYTHONPATH. As the docs say to run it
(`pip install -v`): the output shows what CMake builds and its progress, and CMake configures the
module only (no tests, examples, benchmarks, tools or reference solver in its build folder).

The CMake build goes to MASSSPRING_PIP_BUILD_DIR (ctest: the build folder's name + "-pip", beside
it, so that its compile commands equal the build's and the compiler cache serves them); the venv
to that folder's venv/, made afresh each time. The test prints how long the install took.

Skipped when the Python running it has no venv or pip module (Debian: python3-venv, python3-pip)."""

import os
import re
import shutil
import subprocess
import sys
import time

import pytest

from conftest import SOURCE_DIR


def test_pip_install_builds_and_installs_the_package(tmp_path):
    for module in ("venv", "pip", "setuptools", "wheel"):
        if subprocess.run([sys.executable, "-c", f"import {module}"],
                          capture_output=True).returncode != 0:
            pytest.skip(f"{sys.executable} has no {module} module (Debian: python3-{module})")
    build = os.environ.get("MASSSPRING_PIP_BUILD_DIR") or os.path.join(SOURCE_DIR, "build-pip")
    venv = os.path.join(build, "venv")
    shutil.rmtree(venv, ignore_errors=True)
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", venv], check=True)
    python = os.path.join(venv, "bin", "python")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["MASSSPRING_PIP_BUILD_DIR"] = build
    env["PIP_NO_INDEX"] = "1"  # never download
    started = time.monotonic()
    done = subprocess.run([python, "-m", "pip", "install", "-v", "--no-build-isolation",
                           "--no-deps", "--no-index", SOURCE_DIR],
                          env=env, cwd=tmp_path, capture_output=True, text=True, timeout=1800)
    seconds = time.monotonic() - started
    print(f"pip install took {seconds:.1f} s")
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-4000:]
    # -v shows (on stderr) setup.py's note, CMake's progress and the time it took
    shown = done.stdout + done.stderr
    assert "massspring: CMake builds the target massspring_python only" in shown, shown[-4000:]
    assert "Built target massspring_python" in shown, shown[-4000:]
    assert re.search(r"massspring: massspring_python built in \d+ s", shown), shown[-4000:]
    # only the module's folders were configured
    for folder in ("tests", "examples", "benchmarks", "tools", "reference", "fuzz"):
        assert not os.path.exists(os.path.join(build, folder)), folder
    assert os.path.isdir(os.path.join(build, "python"))

    check = ("import os, massspring, massspring.sweep, massspring._core;"
             "import numpy as np;"
             "s = massspring.MassSpringSystem(np.array([[0.0, 0, 0], [1, 0, 0]]),"
             " np.array([[0, 1]]), 1.0, 10.0);"
             "s.add_force(massspring.Gravity([0, -9.8, 0]));"
             "f = massspring.FastMassSpring(); f.precompute(s, 0.01); assert f.step(s).ok();"
             "assert massspring.Error.__module__ == 'massspring';"
             "print(os.path.dirname(massspring.__file__), massspring.__version__,"
             " os.path.basename(massspring._core.__file__))")
    imported = subprocess.run([python, "-c", check], env=env, cwd=tmp_path, capture_output=True,
                              text=True, timeout=120)
    assert imported.returncode == 0, imported.stderr
    folder, version, core = imported.stdout.split()
    assert folder.startswith(os.path.realpath(venv)) or folder.startswith(venv), folder
    assert core.startswith("_core.") and core.endswith(".so")
    with open(os.path.join(SOURCE_DIR, "include", "massspring", "version.hpp")) as handle:
        header = handle.read()
    for part, value in zip(("MAJOR", "MINOR", "PATCH"), version.split(".")):
        assert f"#define MASSSPRING_VERSION_{part} {value}\n" in header, version
    listed = subprocess.run([python, "-m", "pip", "show", "-f", "massspring"], env=env,
                            capture_output=True, text=True, timeout=120)
    assert "massspring/sweep/driver.py" in listed.stdout, listed.stdout
