#!/usr/bin/env python3
"""scripts/pareto.sh writes a user's run to its own folder: run by ctest (tests/CMakeLists.txt) as

    pareto_script.py SOURCE_DIR WORK_DIR

Checks, with `--dry-run` (which prints the commands and runs none), that
- by default the program writes to out/pareto/ and the tables and plots go there too: nothing
  under docs/;
- --out DIR moves all of it; the program's own arguments pass through;
- --update-docs adds the one command that rewrites docs/ (benchmarks.md's tables, images/), and is
  refused with --quick or --scenes (a partial run would drop tables), before anything runs;
- it installs `scripts/setup.sh pareto`, a set with the compiler, CMake, Eigen, Google Benchmark
  and matplotlib and none of the test, Python-module, fuzzing or browser tools, and its configure
  command succeeds when CMake finds none of the packages it leaves out (run into WORK_DIR) and
  generates the target pareto;
- the scripts state no run time in minutes (one that no measurement backs).
Only the standard library."""

import os
import shlex
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from checks import check, fail  # noqa: E402  (tests/tools/checks.py, shared)

PARETO = {"build-essential", "cmake", "libeigen3-dev", "libbenchmark-dev", "python3",
          "python3-matplotlib"}
NOT_FOR_PARETO = {"doctest-dev", "pybind11-dev", "python3-dev", "python3-numpy", "python3-pytest",
                  "clang", "chromium", "python3-selenium", "nlohmann-json3-dev", "libpugixml-dev",
                  "libcli11-dev", "libjs-three", "libsuitesparse-dev", "python3-dask"}
HIDDEN = ["doctest", "pybind11", "Python", "Python3", "nlohmann_json", "pugixml", "CLI11",
          "CHOLMOD", "Bullet", "ZLIB"]


def main():
    if len(sys.argv) != 3:
        fail(__doc__)
    source, work = sys.argv[1:]
    script = os.path.join(source, "scripts", "pareto.sh")
    with open(script) as handle:
        text = handle.read()
    # never start a real run on a script without --dry-run
    check("--dry-run)" in text, "scripts/pareto.sh has no --dry-run")

    def dry(*args):
        result = subprocess.run([script, "--dry-run", *args], capture_output=True, text=True,
                                timeout=60)
        check(result.returncode == 0, f"{args}: exit {result.returncode} {result.stderr}")
        return [shlex.split(line) for line in result.stdout.splitlines() if line.strip()]

    def program(lines):
        runs = [l for l in lines if l[0].endswith("/pareto")]
        check(len(runs) == 1, f"{len(runs)} runs of the pareto program: {lines}")
        return runs[0]

    def plots(lines):
        return [l[l.index("scripts/plot_pareto.py") + 1:] for l in lines
                if "scripts/plot_pareto.py" in l]

    lines = dry()
    check(lines[0] == ["scripts/setup.sh", "pareto"], f"the first command: {lines[0]}")
    p = program(lines)
    check(p[p.index("--out") + 1] == "out/pareto", f"the default output: {p}")
    check(plots(lines) == [["out/pareto", "out/pareto"]], f"the default plots: {plots(lines)}")
    check(not any("docs" in w for l in lines for w in l), f"a default run names docs/: {lines}")

    lines = dry("--out", "mine", "--quick", "--scenes", "chain,net")
    p = program(lines)
    check(p[p.index("--out") + 1] == "mine" and p[-3:] == ["--quick", "--scenes", "chain,net"],
          f"--out mine --quick --scenes chain,net: {p}")
    check(plots(lines) == [["mine", "mine"]], f"--out mine: {plots(lines)}")

    lines = dry("--update-docs")
    check(plots(lines) == [["out/pareto", "out/pareto"], ["out/pareto", "docs"]],
          f"--update-docs: {plots(lines)}")
    for partial in (["--quick"], ["--scenes", "chain"]):
        result = subprocess.run([script, "--update-docs", *partial], capture_output=True,
                                text=True, timeout=60)
        check(result.returncode == 2 and result.stdout == "" and
              f"pareto.sh: --update-docs needs the full benchmark; {partial[0]}" in result.stderr,
              f"--update-docs {partial}: exit {result.returncode} {result.stderr!r}")

    listed = subprocess.run([os.path.join(source, "scripts", "setup.sh"), "pareto", "--print"],
                            capture_output=True, text=True, timeout=60)
    packages = set(listed.stdout.split())
    check(listed.returncode == 0 and PARETO <= packages and not packages & NOT_FOR_PARETO,
          f"setup.sh pareto: {sorted(packages)}")

    configure = [l for l in dry() if l[:2] == ["cmake", "-S"]]
    check(len(configure) == 1, f"configure commands: {configure}")
    command = configure[0]
    command[command.index("-B") + 1] = work
    shutil.rmtree(work, ignore_errors=True)
    command += [f"-DCMAKE_DISABLE_FIND_PACKAGE_{name}=ON" for name in HIDDEN]
    result = subprocess.run(command, cwd=source, capture_output=True, text=True, timeout=300)
    check(result.returncode == 0, f"{shlex.join(command)}: exit {result.returncode}\n"
                                  f"{result.stderr[-3000:]}")
    targets = subprocess.run(["cmake", "--build", work, "--target", "help"], capture_output=True,
                             text=True, timeout=60).stdout
    check("pareto" in targets.split(), "the configure does not generate the target pareto")
    shutil.rmtree(work, ignore_errors=True)

    for name in ("pareto.sh", "accuracy.sh"):
        with open(os.path.join(source, "scripts", name)) as handle:
            check("minute" not in handle.read(), f"scripts/{name} states a time in minutes")
    print("OK: pareto.sh writes to out/pareto/ (docs/ only with --update-docs, a full run), "
          "installs and configures only what it uses")


if __name__ == "__main__":
    main()
