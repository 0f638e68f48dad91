#!/usr/bin/env python3
"""The README's massspring-simulate commands run as printed after scripts/demo.sh on a fresh
clone: run by ctest (tests/CMakeLists.txt) as

    readme_commands.py SOURCE_DIR

Checks, reading the files only (nothing is built or run), that every command line of the
README's ```sh blocks that runs massspring-simulate names it by the path scripts/demo.sh builds:
demo.sh's build folder (its `build=${BUILD_DIR:-FOLDER}` default), `/tools/massspring-simulate`,
the binary its `"$build"/tools/massspring-simulate` runs, from the target it builds
(`--target massspring_simulate`). Only the standard library."""

import os
import re
import shlex
import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def demo_binary(source):
    """The path, relative to the checkout, of the massspring-simulate scripts/demo.sh builds."""
    with open(os.path.join(source, "scripts", "demo.sh")) as handle:
        text = handle.read()
    default = re.findall(r'^build=\$\{BUILD_DIR:-([^}]+)\}$', text, re.M)
    if len(default) != 1:
        fail(f"scripts/demo.sh: {len(default)} lines `build=${{BUILD_DIR:-FOLDER}}`, not one")
    if not re.search(r'^cmake --build "\$build" .*--target massspring_simulate\b', text, re.M):
        fail("scripts/demo.sh does not build the target massspring_simulate into \"$build\"")
    if '"$build"/tools/massspring-simulate ' not in text:
        fail('scripts/demo.sh does not run "$build"/tools/massspring-simulate')
    return default[0] + "/tools/massspring-simulate"


def readme_commands(source):
    """Every command line (continuations joined) of the README's ```sh blocks."""
    lines, inside, line = [], False, ""
    with open(os.path.join(source, "README.md")) as handle:
        for raw in handle.read().splitlines():
            if inside and raw == "```":
                inside = False
            elif inside:
                line += raw[:-1] + " " if raw.endswith("\\") else raw
                if not raw.endswith("\\"):
                    if line.strip() and not line.lstrip().startswith("#"):
                        lines.append(line.strip())
                    line = ""
            elif raw == "```sh":
                inside = True
    return lines


def main():
    if len(sys.argv) != 2:
        fail(__doc__)
    source = sys.argv[1]
    binary = demo_binary(source)
    runs = [c for c in readme_commands(source)
            if any(w.endswith("massspring-simulate") for w in shlex.split(c, comments=True))]
    if len(runs) < 3:
        fail(f"{len(runs)} README command lines run massspring-simulate")
    for command in runs:
        words = shlex.split(command, comments=True)
        if words[0] != binary:
            fail(f"the README runs {words[0]!r}, scripts/demo.sh builds {binary!r}:\n{command}")
    print(f"OK: {len(runs)} README commands run {binary}, the binary scripts/demo.sh builds")


if __name__ == "__main__":
    main()
