#!/usr/bin/env python3
"""benchmarks/pareto's --scenes: run by ctest (tests/CMakeLists.txt) as

    pareto_scenes.py PARETO WORK_DIR

Checks that
- an unknown scene (`--scenes clot32`, `--scenes chain,bogus,clot32`) is refused before anything
  runs or is written: exit 2, one line naming every unknown name and the valid ones, no output
  folder created;
- a scene --quick leaves out (`--quick --scenes chain,cloth32`) is named on stderr, and the
  others run (`--references-only`: references.csv holds chain only);
- `--quick --scenes cloth32` leaves nothing to run: refused, named, nothing written.
Only the standard library."""

import csv
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from checks import check, fail  # noqa: E402  (tests/tools/checks.py, shared)

KNOWN = "(the scenes: chain, net, orbit, cloth32, cloth64)"


def run(pareto, args, work):
    return subprocess.run([pareto] + args, cwd=work, capture_output=True, text=True, timeout=600)


def main():
    if len(sys.argv) != 3:
        fail(__doc__)
    pareto, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for args, expected in (
            (["--scenes", "clot32"], "pareto: --scenes: unknown scene clot32 " + KNOWN),
            (["--scenes", "chain,bogus,clot32"],
             "pareto: --scenes: unknown scenes bogus, clot32 " + KNOWN),
            (["--quick", "--scenes", "cloth32"],
             "pareto: --quick leaves out cloth32 (the cloths run in the full benchmark only)\n"
             "pareto: --scenes cloth32 with --quick: no scene left to run")):
        result = run(pareto, args + ["--out", "o", "--cache", "c"], work)
        check(result.returncode == 2 and result.stderr == expected + "\n",
              f"{args}: exit {result.returncode}, stderr {result.stderr!r}, expected {expected!r}")
        check(os.listdir(work) == [], f"{args}: wrote {os.listdir(work)}")
    result = run(pareto, ["--quick", "--scenes", "chain,cloth32", "--references-only", "--out",
                          "o", "--cache", "c"], work)
    check(result.returncode == 0, f"--quick --scenes chain,cloth32: exit {result.returncode} "
                                  f"{result.stderr}")
    check("pareto: --quick leaves out cloth32 (the cloths run in the full benchmark only)"
          in result.stderr.splitlines(), f"cloth32 not named: {result.stderr!r}")
    with open(os.path.join(work, "o", "references.csv"), newline="") as handle:
        scenes = [row["scene"] for row in csv.DictReader(handle)]
    check(scenes == ["chain"], f"references for {scenes}, expected chain only")
    shutil.rmtree(work, ignore_errors=True)
    print("OK: unknown scenes refused with the valid names; scenes --quick leaves out are named")


if __name__ == "__main__":
    main()
