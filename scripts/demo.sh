#!/usr/bin/env bash
# The main job: simulate the project's own flag-sized cloth (3,000 points, two corners pinned,
# 300 frames at dt = 1/30, gravity), time every step, write frames and a trajectory, and render
# pictures. Prints the median milliseconds per frame.
# Output: out/demo/ (frames/*.obj, trajectory.csv, cloth.png, cloth.gif)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/setup.sh

build=${BUILD_DIR:-build}
out=out/demo
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" --target massspring_simulate
# Debian's python3 (with python3-matplotlib), not whatever python3 comes first on PATH.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
rm -rf "$out"
mkdir -p "$out"
"$build"/examples/massspring-simulate examples/scenes/flag.json \
  --frames 300 --dt 0.033333333333333333 --iterations 50 --gravity 0,-9.8,0 \
  --out "$out/frames" --every 3 --csv "$out/trajectory.csv"
# The picture: the first second (where the motion is), t in seconds, pins marked; the GIF: all 10 s.
"$python" scripts/render.py "$out/frames" --dt 0.033333333333333333 --until 1 --panels 6 --size 2.6 \
  --png "$out/cloth.png" --gif "$out/cloth.gif"
echo "demo: pictures in $out/cloth.png and $out/cloth.gif"
