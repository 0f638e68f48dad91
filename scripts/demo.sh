#!/usr/bin/env bash
# The main job: drape the project's own cloth (31 x 31 points) over a ball onto a floor (1.5 s,
# 45 steps of 1/30 s of the local-global solver, 10 iterations, contact and friction inside the
# iteration, self-collision on), time every step, write frames and a trajectory, and render
# pictures with the colliders. Prints the median milliseconds per step.
# Installs only what it uses (scripts/setup.sh demo: no test, benchmark or fuzzing tools) and
# builds only massspring-simulate, in its own build folder (tests, benchmarks and the Python module
# off, so that their packages are not needed).
# Output: out/demo/ (frames/*.obj, trajectory.csv, drape.html, drape.png, drape.gif); open
# drape.html in a web browser to orbit, zoom and play the drape (one file, works offline). A
# rerun first removes those files of the previous run (scripts/demo_clean.sh, which names them),
# and nothing else.
# Env: BUILD_DIR (default build-demo)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/setup.sh demo

build=${BUILD_DIR:-build-demo}
out=out/demo
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DMASSSPRING_BUILD_TESTS=OFF \
  -DMASSSPRING_BUILD_BENCHMARKS=OFF -DMASSSPRING_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" --target massspring_simulate
# Debian's python3 (with python3-matplotlib), not whatever python3 comes first on PATH.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
# the previous demo's files only (named as it removes them); anything else in out/demo stays
scripts/demo_clean.sh "$out"
mkdir -p "$out"
# The drape (examples/scenes/drape.json): a cloth dropped over a sphere onto a floor, friction 0.3
# on both; the scene carries its gravity. At the tool's usual step, 1/30 s (the scene's own is
# 1/200), with self-collision 4 mm thick and the solver's defaults (docs/contact.md, "Defaults").
# 1.5 s, every frame.
"$build"/tools/massspring-simulate examples/scenes/drape.json \
  --dt 0.0333333 --duration 1.5 --self-collision 0.004 \
  --out "$out/frames" --every 1 --csv "$out/trajectory.csv" --html "$out/drape.html"
"$python" scripts/render.py "$out/frames" --dt 0.0333333 --until 1.5 --panels 4 --size 2.6 \
  --scene examples/scenes/drape.json --png "$out/drape.png" --gif "$out/drape.gif"
echo "demo: pictures in $out/drape.png and $out/drape.gif; open $out/drape.html in a browser"
