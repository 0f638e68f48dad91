#!/usr/bin/env bash
# Runs every example scene with massspring-simulate and renders it into docs/images/ex_*.png and
# ex_*.gif (docs/examples.md shows them). Frames go to out/examples/ (not committed), with a page
# per scene, out/examples/NAME.html, that plays it in a web browser (massspring-simulate --html).
#   scripts/examples.sh            # build what is needed, run, render
# Needs python3-matplotlib (Debian's /usr/bin/python3); scripts/setup.sh installs it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/setup.sh

build=${BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" \
  --target massspring_simulate massspring_make_scenes massspring_pole
python=/usr/bin/python3
[ -x "$python" ] || python=python3
simulate="$build/tools/massspring-simulate"
render() { "$python" scripts/render.py "$@"; }
out=out/examples
images=docs/images
rm -rf "$out"
mkdir -p "$out" "$images"

# The scenes are generated; regenerate them so the pictures show what the generator writes.
"$build/tools/massspring-make-scenes" examples/scenes examples/scenes_xml >/dev/null

# Orbit: the same scene with explicit and with symplectic Euler (dt = 0.01, 20 s, 5 orbits).
"$simulate" examples/scenes_xml/orbit.xml --integrator forward-euler --every 5 --out "$out/orbit_forward"
"$simulate" examples/scenes_xml/orbit.xml --integrator symplectic-euler --every 5 --out "$out/orbit_symplectic" \
  --html "$out/orbit.html"
render "$out/orbit_forward" "$out/orbit_symplectic" --labels "forward Euler,symplectic Euler" \
  --trails --frame-time 0.05 --panels 3 --png "$images/ex_orbit.png"
rm -rf "$out/orbit_forward" "$out/orbit_symplectic"  # coarser frames for a small GIF
"$simulate" examples/scenes_xml/orbit.xml --integrator forward-euler --every 25 --out "$out/orbit_forward"
"$simulate" examples/scenes_xml/orbit.xml --integrator symplectic-euler --every 25 --out "$out/orbit_symplectic"
render "$out/orbit_forward" "$out/orbit_symplectic" --labels "forward Euler,symplectic Euler" \
  --trails --frame-time 0.25 --gif "$images/ex_orbit.gif" --fps 10 --size 2.8

# Cantilever: a clamped truss sagging under gravity (symplectic Euler, dt = 0.5 ms, 6 s).
"$simulate" examples/scenes_xml/cantilever.xml --every 300 --out "$out/cantilever" --html "$out/cantilever.html"
render "$out/cantilever" --frame-time 0.15 --panels 4 --png "$images/ex_cantilever.png" \
  --gif "$images/ex_cantilever.gif" --size 3

# Decreasing rest length: the hanging chain's rest lengths shrink as exp(-0.1 t).
"$simulate" examples/scenes_xml/shrinking_chain.xml --shrink 0.1 --every 20 --out "$out/shrinking" \
  --html "$out/shrinking_chain.html"
render "$out/shrinking" --frame-time 0.2 --panels 4 --png "$images/ex_shrinking_chain.png" \
  --gif "$images/ex_shrinking_chain.gif" --size 3

# Damping series: b = 0, 0.1, ..., 1 (top to bottom).
"$simulate" examples/scenes_xml/damping_series.xml --every 10 --out "$out/damping" --html "$out/damping_series.html"
render "$out/damping" --frame-time 0.05 --panels 4 --png "$images/ex_damping_series.png" \
  --lengths "$images/ex_damping_lengths.png" --size 3

# 3D scenes like the JSON+OBJ scenes (docs/glossary.md), with the local-global solver, gravity
# 9.8 m/s^2, dt = 1/30.
for scene in chain net; do
  "$simulate" "examples/scenes/$scene.json" --steps 90 --every 3 --out "$out/$scene" --html "$out/$scene.html"
  render "$out/$scene" --panels 4 --png "$images/ex_$scene.png"
done
"$simulate" examples/scenes/flag.json --steps 90 --every 10 --iterations 20 --out "$out/flag" \
  --html "$out/flag.html"
render "$out/flag" --panels 4 --png "$images/ex_flag.png" --gif "$images/ex_flag.gif"

# Contact with obstacles (docs/contact.md): the local-global solver, dt = 1/200 s (the motion per step
# stays below the points' spacing), 2 s; the colliders drawn from each scene.
for scene in drape table tilted mesh; do
  "$simulate" "examples/scenes/$scene.json" --duration 2 --dt 0.005 --every 10 --out "$out/$scene" \
    --html "$out/$scene.html"
  render "$out/$scene" --dt 0.005 --panels 4 --size 2.4 --scene "examples/scenes/$scene.json" \
    --png "$images/ex_$scene.png" --gif "$images/ex_$scene.gif" --fps 10
done

# The drape at the tool's usual step, dt = 1/30 s, with the solver's defaults (contact and
# friction inside the iteration: docs/contact.md) and self-collision 4 mm thick, 2 s.
"$simulate" examples/scenes/drape.json --duration 2 --dt 0.0333333 --self-collision 0.004 \
  --out "$out/drape_1_30" \
  --html "$out/drape_1_30.html"
render "$out/drape_1_30" --dt 0.0333333 --panels 4 --size 2.4 --scene examples/scenes/drape.json \
  --png "$images/ex_drape_1_30.png" --gif "$images/ex_drape_1_30.gif" --fps 10

# FOSSSim Theme 2 (docs/contact.md): the same box of balls with each collision response, 4 s.
for kind in simple penalty continuous hybrid; do
  dt=0.002 every=25
  [ "$kind" = penalty ] && dt=0.0005 every=100  # its stiff penalty springs take a shorter step
  "$simulate" "examples/scenes_xml/balls_$kind.xml" --every "$every" --out "$out/balls_$kind" \
    --html "$out/balls_$kind.html"
  render "$out/balls_$kind" --dt "$dt" --panels 4 --size 2.4 \
    --scene "examples/scenes_xml/balls_$kind.xml" --png "$images/ex_balls_$kind.png" \
    --gif "$images/ex_balls_$kind.gif" --fps 12
done

# A flag wound onto a turning pole (tools/pole.cpp): pins moved with the pole, dt = 2 ms, 5 s.
"$build/tools/massspring-pole" --out "$out/pole" --every 50
render "$out/pole" --dt 0.002 --panels 4 --size 2.4 --scene "$out/pole/pole.json" \
  --png "$images/ex_pole.png" --gif "$images/ex_pole.gif" --fps 10

ls -l "$images"/ex_*
