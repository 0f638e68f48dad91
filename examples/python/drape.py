#!/usr/bin/python3
"""Drapes a cloth over a ball from Python and saves a picture of it.

    PYTHONPATH=build/python python3 examples/python/drape.py [--scene examples/scenes/drape.json]
        [--frames 300] [--dt 0.005] [--iterations 10] [--png out/python/drape.png]

The scene (a JSON+OBJ file: a 31 x 31 cloth above a sphere on a floor) is loaded with
massspring.load_scene_file, gravity (9.8 m/s^2 down) is added as a force term, and the
local-global solver (FastMassSpring) runs with dt = 1/200 s (as scripts/demo.sh: a step's motion
stays below the points' spacing, so no point passes through the ball in one step; at 1/30 s the
cloth would fall through it, docs/contact.md). The PNG shows four frames
spread over the run: the cloth's faces, and the colliders drawn from the scene's own "colliders"
list. Needs the built module (scripts/test.sh builds it into build/python) and Debian's
python3-numpy and python3-matplotlib.
"""

import argparse
import json
import os
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import massspring as ms  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def draw_colliders(ax, scene_path):
    """The scene's spheres as wireframes, its planes as a grey floor patch (y up is drawn up)."""
    with open(scene_path) as handle:
        colliders = json.load(handle).get("colliders", [])
    for c in colliders:
        if c.get("type") == "sphere":
            u, v = np.mgrid[0:2 * np.pi:24j, 0:np.pi:12j]
            r, (cx, cy, cz) = c["radius"], c["center"]
            ax.plot_wireframe(cx + r * np.cos(u) * np.sin(v), cz + r * np.sin(u) * np.sin(v),
                              cy + r * np.cos(v), color="0.6", linewidth=0.4)
        elif c.get("type") == "plane" and c["normal"] == [0, 1, 0]:
            y = c["point"][1]
            xs, zs = np.meshgrid([-0.8, 0.8], [-0.8, 0.8])
            ax.plot_surface(xs, zs, np.full_like(xs, y), color="0.85", alpha=0.5)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    parser.add_argument("--scene", default=os.path.join(ROOT, "examples", "scenes", "drape.json"))
    parser.add_argument("--frames", type=int, default=300)
    parser.add_argument("--dt", type=float, help="time step [s] (default: the scene's \"dt\", "
                        "else 0.005)")
    parser.add_argument("--iterations", type=int,
                        help="local-global iterations per step (default: the solver's, 10)")
    parser.add_argument("--png", default=os.path.join("out", "python", "drape.png"))
    args = parser.parse_args()

    loaded = ms.load_scene_file(args.scene)
    system = loaded.system
    if "gravity" not in system.forces:  # drape.json carries its own
        system.add_force(ms.Gravity([0, -9.8, 0]))  # [m/s^2], on each point's mass
    solver = ms.FastMassSpring()
    if args.iterations is not None:
        solver.options.iterations = args.iterations
    dt = args.dt or loaded.dt or 0.005  # [s]
    solver.precompute(system, dt)

    panels = sorted({0, args.frames // 3, 2 * args.frames // 3, args.frames})
    shots = {0: system.positions.copy()}  # .copy(): the view follows later steps
    start = time.perf_counter()
    for frame in range(1, args.frames + 1):
        report = solver.step(system)
        if not report.ok():
            sys.exit(f"frame {frame}: the step failed ({report})")
        if frame in panels:
            shots[frame] = system.positions.copy()
    seconds = time.perf_counter() - start
    print(f"{args.scene}: {system.num_points} points, {system.num_springs} springs, "
          f"{system.num_colliders} colliders; {args.frames} frames in {seconds:.2f} s "
          f"({1000 * seconds / max(args.frames, 1):.2f} ms per frame)")

    faces = loaded.faces
    fig = plt.figure(figsize=(4 * len(panels), 4.2))
    for k, frame in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), k + 1, projection="3d")
        x = shots[frame]
        # the simulation's y is up: draw (x, z, y)
        polygons = [[(x[i, 0], x[i, 2], x[i, 1]) for i in face] for face in faces]
        ax.add_collection3d(Poly3DCollection(polygons, facecolor="#1c4587", edgecolor="#0b2447",
                                             linewidth=0.1, alpha=0.9))
        draw_colliders(ax, args.scene)
        ax.set_xlim(-0.8, 0.8)
        ax.set_ylim(-0.8, 0.8)
        ax.set_zlim(0, 1.2)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("z [m]")
        ax.set_zlabel("y [m]")
        ax.set_title(f"t = {frame * dt:.2f} s")
    fig.suptitle("massspring from Python: a cloth draped over a ball (FastMassSpring, "
                 f"{args.iterations} iterations per frame)")
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.png)), exist_ok=True)
    fig.savefig(args.png, dpi=100)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
