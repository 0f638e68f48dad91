#!/usr/bin/env python3
"""scripts/demo.sh removes only what it wrote: run by ctest (tests/CMakeLists.txt) as

    demo_clean.py SOURCE_DIR WORK_DIR

Checks that
- demo.sh removes nothing itself (no `rm`) and clears its output folder with
  `scripts/demo_clean.sh "$out"` before the run;
- scripts/demo_clean.sh, on a folder holding every file the demo writes (trajectory.csv,
  drape.html, drape.png, drape.gif, the .tmp of the first two, frames/frame_NNNNN.obj and .tmp)
  beside files that are not the demo's (in the folder, in frames/, a subfolder), removes exactly
  the demo's, keeps every other byte for byte, says on one line what it removes, and exits 0;
- frames/ is removed when that leaves it empty, kept otherwise;
- a second run (nothing of the demo's left) and a folder that does not exist: exit 0, silent.
Only the standard library."""

import hashlib
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from checks import check, fail  # noqa: E402  (tests/tools/checks.py, shared)

DEMO_FILES = ["trajectory.csv", "trajectory.csv.tmp", "drape.html", "drape.html.tmp",
              "drape.png", "drape.gif"] + [f"frames/frame_{k:05d}.obj" for k in range(46)] + \
             ["frames/frame_00046.obj.tmp"]
FOREIGN = ["notes.txt", "drape.png.bak", "my_trajectory.csv", "frames/mine.obj",
           "frames/frame_1.obj", "keep/frame_00000.obj", "keep/trajectory.csv"]


def snapshot(folder):
    out = {}
    for root, dirs, files in os.walk(folder):
        for d in dirs:
            out[os.path.relpath(os.path.join(root, d), folder) + "/"] = "dir"
        for f in files:
            with open(os.path.join(root, f), "rb") as handle:
                out[os.path.relpath(os.path.join(root, f), folder)] = hashlib.sha256(
                    handle.read()).hexdigest()
    return out


def fill(folder, names):
    for name in names:
        path = os.path.join(folder, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as handle:
            handle.write(name + "\n")


def clean(source, folder):
    return subprocess.run([os.path.join(source, "scripts", "demo_clean.sh"), folder],
                          capture_output=True, text=True, timeout=60)


def main():
    if len(sys.argv) != 3:
        fail(__doc__)
    source, work = sys.argv[1:]
    with open(os.path.join(source, "scripts", "demo.sh")) as handle:
        lines = [l.strip() for l in handle if l.strip() and not l.lstrip().startswith("#")]
    check(not any(l.split()[0] == "rm" for l in lines),
          f"scripts/demo.sh removes files itself: {[l for l in lines if l.split()[0] == 'rm']}")
    check('scripts/demo_clean.sh "$out"' in lines,
          'scripts/demo.sh does not clear its output with scripts/demo_clean.sh "$out"')
    shutil.rmtree(work, ignore_errors=True)
    out = os.path.join(work, "out", "demo")
    # the demo's files beside foreign ones: only the demo's go, and the message says which
    fill(out, DEMO_FILES + FOREIGN)
    before = snapshot(out)
    result = clean(source, out)
    check(result.returncode == 0, f"exit {result.returncode}: {result.stderr}")
    after = snapshot(out)
    kept = {k: v for k, v in before.items() if k in FOREIGN or k.endswith("/")}
    check(after == kept, f"left {sorted(after)}, expected {sorted(kept)}")
    message = result.stdout.strip()
    check(len(message.splitlines()) == 1 and message.startswith("demo: removing ") and
          out in message and "47 frame files" in message and
          all(n in message for n in DEMO_FILES if "/" not in n) and
          not any(n in message for n in FOREIGN),
          f"the message {message!r}")
    # a second run: nothing of the demo's left, nothing said, nothing changed
    result = clean(source, out)
    check(result.returncode == 0 and result.stdout == "" and snapshot(out) == after,
          f"second run: exit {result.returncode} {result.stdout!r}")
    # frames/ holding only frame files goes with them
    shutil.rmtree(out)
    fill(out, DEMO_FILES + ["notes.txt"])
    result = clean(source, out)
    check(result.returncode == 0 and sorted(snapshot(out)) == ["notes.txt"],
          f"only notes.txt should stay: {sorted(snapshot(out))}")
    # a folder that does not exist (a first run)
    result = clean(source, os.path.join(work, "nothing"))
    check(result.returncode == 0 and result.stdout == "" and
          not os.path.exists(os.path.join(work, "nothing")), "a missing folder")
    shutil.rmtree(work, ignore_errors=True)
    print("OK: demo_clean.sh removes the demo's files only, names them, keeps every other file")


if __name__ == "__main__":
    main()
