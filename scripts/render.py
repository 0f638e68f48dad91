#!/usr/bin/python3
"""Renders OBJ frames written by massspring-simulate into pictures.

    python3 scripts/render.py FRAMES_DIR [--png strip.png] [--gif anim.gif] [--panels 4]

FRAMES_DIR holds frame_NNNNN.obj files (vertices, polygons and 2-vertex edges, 1-based). The PNG
is a strip of --panels frames spread evenly over the run; the GIF shows every frame. The y axis
of the simulation is drawn upwards. Needs python3-matplotlib (Debian).
"""

import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import animation  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402


def read_obj(path):
    """Returns (vertices, polygons, edges) of an OBJ file, 0-based."""
    vertices, polygons, edges = [], [], []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        try:
            if parts[0] == "v":
                vertices.append(tuple(float(p) for p in parts[1:4]))
            elif parts[0] in ("f", "l"):
                ids = [int(p.split("/")[0]) for p in parts[1:]]
                ids = [i - 1 if i > 0 else len(vertices) + i for i in ids]
                if parts[0] == "l" or len(ids) == 2:
                    edges.extend(zip(ids, ids[1:]))
                else:
                    polygons.append(ids)
        except ValueError as error:
            sys.exit(f"{path}:{number}: {error}")
    return vertices, polygons, edges


def to_view(p):
    """Simulation (x, y, z) to plot coordinates with y up."""
    return (p[0], p[2], p[1])


def draw(ax, frame, limits, title):
    vertices, polygons, edges = frame
    ax.cla()
    view = [to_view(v) for v in vertices]
    if polygons:
        faces = [[view[i] for i in poly] for poly in polygons]
        ax.add_collection3d(Poly3DCollection(faces, facecolor="#6fa8dc", edgecolor="#1c4587",
                                             linewidths=0.1, alpha=0.9))
    if edges:
        ax.add_collection3d(Line3DCollection([(view[i], view[j]) for i, j in edges],
                                             colors="#1c4587", linewidths=0.6))
    if not polygons and not edges:
        ax.scatter(*zip(*view), s=4)
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_zlim(*limits[2])
    ax.set_box_aspect([hi - lo for lo, hi in limits])
    ax.set_xlabel("x")
    ax.set_ylabel("z")
    ax.set_zlabel("y")
    ax.set_title(title, fontsize=9)
    ax.view_init(elev=18, azim=-60)


def bounds(frames):
    view = [to_view(v) for vertices, _, _ in frames for v in vertices]
    limits = []
    for axis in range(3):
        lo = min(p[axis] for p in view)
        hi = max(p[axis] for p in view)
        pad = 0.05 * max(hi - lo, 1e-3)
        limits.append((lo - pad, hi + pad))
    return limits


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("frames", type=pathlib.Path, help="folder of frame_*.obj files")
    parser.add_argument("--png", type=pathlib.Path, help="write a strip of frames here")
    parser.add_argument("--gif", type=pathlib.Path, help="write an animation here")
    parser.add_argument("--panels", type=int, default=4, help="frames in the PNG strip (4)")
    parser.add_argument("--fps", type=int, default=10, help="GIF frames per second (10)")
    args = parser.parse_args()

    files = sorted(args.frames.glob("frame_*.obj"))
    if not files:
        sys.exit(f"render.py: no frame_*.obj files in {args.frames}")
    frames = [read_obj(f) for f in files]
    limits = bounds(frames)

    if args.png:
        count = max(1, min(args.panels, len(frames)))
        picks = [round(k * (len(frames) - 1) / max(count - 1, 1)) for k in range(count)]
        fig = plt.figure(figsize=(3.2 * count, 3.4))
        for panel, index in enumerate(picks):
            ax = fig.add_subplot(1, count, panel + 1, projection="3d")
            draw(ax, frames[index], limits, files[index].stem)
        fig.tight_layout()
        fig.savefig(args.png, dpi=110)
        plt.close(fig)
        print(f"render.py: wrote {args.png}")
    if args.gif:
        fig = plt.figure(figsize=(4.5, 4))
        ax = fig.add_subplot(projection="3d")
        movie = animation.FuncAnimation(
            fig, lambda k: draw(ax, frames[k], limits, files[k].stem), frames=len(frames))
        movie.save(args.gif, writer=animation.PillowWriter(fps=args.fps))
        plt.close(fig)
        print(f"render.py: wrote {args.gif}")


if __name__ == "__main__":
    main()
