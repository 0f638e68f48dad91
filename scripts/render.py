#!/usr/bin/python3
"""Renders OBJ frames written by massspring-simulate into pictures.

    python3 scripts/render.py FRAMES_DIR [FRAMES_DIR ...] [--png strip.png] [--gif anim.gif]
        [--panels 4] [--labels a,b] [--trails] [--lengths lengths.png --frame-time S]
        [--dt S --until S]

FRAMES_DIR holds frame_NNNNN.obj files (vertices, polygons and 2-vertex edges, 1-based). The PNG
is a strip of --panels frames spread evenly over the run; the GIF shows every frame. The y axis
of the simulation is drawn upwards. Scenes whose z is 0 throughout (FOSSSim's 2D scenes) are drawn
in 2D; several FRAMES_DIRs (2D only) are overlaid in one picture, one colour each (--labels names
them), and --trails draws the path of every moving point so far. --lengths plots every edge's
length against time (frame number times --frame-time seconds) for the first FRAMES_DIR.
With --dt (the time step: frame_NNNNN.obj is at t = NNNNN x dt) panels are titled with the time in
seconds, and --until T spreads the PNG's panels over 0..T s (where the motion is) instead of the
whole run. In 3D, points that never move (pinned) are marked, and the axes are labelled in metres.
--scene SCENE.json draws the scene's "colliders" (docs/scenes.md) in grey under the cloth: planes,
spheres, capsules, boxes and meshes, moved by their velocities to each frame's time (with --dt;
without it they are drawn where the scene puts them). --scene SCENE.xml (a 2D FOSSSim scene) draws
its particles as discs of their radii, its edges as capsules of theirs, and its half-planes shaded
on their solid side.
Needs python3-matplotlib (Debian).
"""

import argparse
import json
import math
import pathlib
import sys
import xml.etree.ElementTree as ElementTree

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import animation  # noqa: E402
from matplotlib.collections import LineCollection, PatchCollection  # noqa: E402
from matplotlib.patches import Circle, Polygon  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

COLOURS = ["#1c4587", "#cc4125", "#38761d", "#b45f06", "#674ea7"]


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


def rotation(w, t):
    """exp([w] t) (Rodrigues): the rotation by |w| t about w, as rows."""
    angle = math.sqrt(sum(c * c for c in w)) * t
    if angle == 0:
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    k = [c * t / angle for c in w]
    s, c = math.sin(angle), 1 - math.cos(angle)
    x, y, z = k
    return [[1 - c * (y * y + z * z), -s * z + c * x * y, s * y + c * x * z],
            [s * z + c * x * y, 1 - c * (x * x + z * z), -s * x + c * y * z],
            [-s * y + c * x * z, s * x + c * y * z, 1 - c * (x * x + y * y)]]


def apply(r, p):
    return [sum(r[i][j] * p[j] for j in range(3)) for i in range(3)]


def quaternion(q):
    w, x, y, z = (c / math.sqrt(sum(c * c for c in q)) for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def read_colliders(scene):
    """The scene's colliders as (reference point, local polygons around it, velocity, angular
    velocity, is_plane): polygons in the collider's frame, moved at draw time."""
    data = json.loads(scene.read_text())
    out = []
    for c in data.get("colliders", []):
        kind = c["type"]
        polys, ref = [], None
        ring = [(math.cos(2 * math.pi * k / 16), math.sin(2 * math.pi * k / 16)) for k in range(17)]

        def ball(center, r, lats=8):
            for i in range(lats):
                a0, a1 = math.pi * i / lats - math.pi / 2, math.pi * (i + 1) / lats - math.pi / 2
                for (c0, s0), (c1, s1) in zip(ring, ring[1:]):
                    polys.append([[center[0] + r * math.cos(a) * cc, center[1] + r * math.sin(a),
                                   center[2] + r * math.cos(a) * ss]
                                  for a, cc, ss in ((a0, c0, s0), (a0, c1, s1), (a1, c1, s1),
                                                    (a1, c0, s0))])
        if kind == "plane":
            ref, n = c["point"], c["normal"]
            polys = [n]  # drawn across the view at draw time
        elif kind == "sphere":
            ref = c["center"]
            ball([0, 0, 0], c["radius"])
        elif kind == "capsule":
            a, b, r = c["a"], c["b"], c["radius"]
            ref = [(a[k] + b[k]) / 2 for k in range(3)]
            h = [(b[k] - a[k]) / 2 for k in range(3)]
            length = math.sqrt(sum(x * x for x in h)) or 1.0
            d = [x / length for x in h]
            e = [0, 0, 1] if abs(d[2]) < 0.9 else [1, 0, 0]
            u = [d[1] * e[2] - d[2] * e[1], d[2] * e[0] - d[0] * e[2], d[0] * e[1] - d[1] * e[0]]
            un = math.sqrt(sum(x * x for x in u))
            u = [x / un for x in u]
            v = [d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]]
            for (c0, s0), (c1, s1) in zip(ring, ring[1:]):
                polys.append([[sign * h[k] + r * (cc * u[k] + ss * v[k]) for k in range(3)]
                              for sign, cc, ss in ((-1, c0, s0), (-1, c1, s1), (1, c1, s1),
                                                   (1, c0, s0))])
            ball([-x for x in h], r)
            ball(h, r)
        elif kind == "box":
            ref, e = c["center"], c["half_extents"]
            r = quaternion(c.get("rotation", [1, 0, 0, 0]))
            corner = [[apply(r, [sx * e[0], sy * e[1], sz * e[2]]) for sz in (-1, 1)]
                      for sx in (-1, 1) for sy in (-1, 1)]  # corner[2 sx + sy][sz]
            for axis in range(3):
                for side in (0, 1):
                    quad = []
                    for i, j in ((0, 0), (0, 1), (1, 1), (1, 0)):
                        idx = [0, 0, 0]
                        idx[axis] = side
                        free = [k for k in range(3) if k != axis]
                        idx[free[0]], idx[free[1]] = i, j
                        quad.append(corner[2 * idx[0] + idx[1]][idx[2]])
                    polys.append(quad)
        elif kind == "mesh":
            vertices, polygons, _ = read_obj(scene.parent / c["obj"])
            lo = [min(v[k] for v in vertices) for k in range(3)]
            hi = [max(v[k] for v in vertices) for k in range(3)]
            ref = [(lo[k] + hi[k]) / 2 for k in range(3)]
            polys = [[[vertices[i][k] - ref[k] for k in range(3)] for i in poly]
                     for poly in polygons]
        out.append((ref, polys, c.get("velocity", [0, 0, 0]),
                    c.get("angular_velocity", [0, 0, 0]), kind == "plane"))
    return out


def draw_colliders(ax, colliders, t, limits):
    """The colliders at time t (seconds), in grey."""
    for ref, polys, v, w, plane in colliders:
        r = rotation(w, t)
        origin = [ref[k] + v[k] * t for k in range(3)]
        if plane:
            n = apply(r, polys[0])
            centre = [(lo + hi) / 2 for lo, hi in limits]  # view coordinates: x, z, y
            centre = [centre[0], centre[2], centre[1]]
            nn = math.sqrt(sum(x * x for x in n))
            n = [x / nn for x in n]
            dist = sum((centre[k] - origin[k]) * n[k] for k in range(3))
            p = [centre[k] - dist * n[k] for k in range(3)]
            e = [1, 0, 0] if abs(n[0]) < 0.9 else [0, 0, 1]
            u = [n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]]
            un = math.sqrt(sum(x * x for x in u))
            u = [x / un for x in u]
            b = [n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]]
            size = max(hi - lo for lo, hi in limits) / 2
            quad = [[p[k] + size * (i * u[k] + j * b[k]) for k in range(3)]
                    for i, j in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
            world = [quad]
        else:
            world = [[[origin[k] + q[k] for k in range(3)] for q in (apply(r, x) for x in poly)]
                     for poly in polys]
        ax.add_collection3d(Poly3DCollection([[to_view(q) for q in poly] for poly in world],
                                             facecolor="#b7b7b7", edgecolor="#888888",
                                             linewidths=0.1, alpha=0.35))


def to_view(p):
    """Simulation (x, y, z) to plot coordinates with y up."""
    return (p[0], p[2], p[1])


def draw(ax, frame, limits, title, pinned=(), legend=False, colliders=(), t=0.0):
    vertices, polygons, edges = frame
    ax.cla()
    if colliders:
        draw_colliders(ax, colliders, t, limits)
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
    if pinned:
        ax.scatter(*zip(*[view[i] for i in pinned]), s=28, color="#cc0000", marker="o",
                   depthshade=False, label="pinned", zorder=10)
        if legend:
            ax.legend(loc="upper right", fontsize=7, handletextpad=0.2, borderpad=0.3)
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_zlim(*limits[2])
    ax.set_box_aspect([hi - lo for lo, hi in limits], zoom=0.85)
    ax.set_xlabel("x [m]", fontsize=8, labelpad=2)
    ax.set_ylabel("z [m]", fontsize=8, labelpad=2)
    ax.set_zlabel("y [m]", fontsize=8, labelpad=2)
    ax.tick_params(labelsize=6, pad=0)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):  # few ticks: no overlapping labels
        axis.set_major_locator(MaxNLocator(4))
    ax.set_title(title, fontsize=10)
    ax.view_init(elev=18, azim=-60)


def fixed_points(frames):
    """Points at the same place in every frame (pinned), when there are several frames."""
    if len(frames) < 2:
        return []
    first = frames[0][0]
    return [i for i in range(len(first)) if all(f[0][i] == first[i] for f in frames[1:])]


def panel_picks(numbers, panels, dt=None, until=None):
    """Indices of the frames shown in a strip of `panels`: spread evenly over the whole run, or
    with dt and until over the frames at t = number x dt <= until."""
    last = len(numbers) - 1
    if until is not None:
        last = max(k for k in range(len(numbers)) if numbers[k] * dt <= until + 1e-9)
    count = max(1, min(panels, last + 1))
    return [round(k * last / max(count - 1, 1)) for k in range(count)]


def bounds(frames):
    view = [to_view(v) for vertices, _, _ in frames for v in vertices]
    limits = []
    for axis in range(3):
        lo = min(p[axis] for p in view)
        hi = max(p[axis] for p in view)
        pad = 0.05 * max(hi - lo, 1e-3)
        limits.append((lo - pad, hi + pad))
    return limits


def is_flat(runs):
    """True when every vertex of every frame has z == 0."""
    return all(v[2] == 0 for frames in runs for vertices, _, _ in frames for v in vertices)


def read_scene_2d(path):
    """A FOSSSim XML scene's particle radii, edge radii and half-planes (FOSSSim's defaults:
    radius 0.1 m, edge radius 0.015 m)."""
    root = ElementTree.parse(path).getroot()
    radii = [float(p.get("radius", 0.1)) for p in root.iter("particle")]
    edge_radii = [float(e.get("radius", 0.015)) for e in root.iter("edge")]
    planes = [tuple(float(h.get(a, 0)) for a in ("px", "py", "nx", "ny"))
              for h in root.iter("halfplane")]
    return {"radii": radii, "edge_radii": edge_radii, "halfplanes": planes}


def bounds_2d(runs, scene2d=None):
    radii = scene2d["radii"] if scene2d else []
    def r(p):
        return radii[p] if p < len(radii) else 0.0
    xs = [v[0] + s * r(p) for frames in runs for vertices, _, _ in frames
          for p, v in enumerate(vertices) for s in (-1, 1)]
    ys = [v[1] + s * r(p) for frames in runs for vertices, _, _ in frames
          for p, v in enumerate(vertices) for s in (-1, 1)]
    pad = 0.06 * max(max(xs) - min(xs), max(ys) - min(ys), 1e-3)
    return (min(xs) - pad, max(xs) + pad), (min(ys) - pad, max(ys) + pad)


def draw_scene_2d(ax, scene2d, vertices, edges, limits, colour):
    """Half-planes shaded on their solid side; edges as capsules and particles as discs of their
    radii (data units)."""
    (x0, x1), (y0, y1) = limits
    far = 4 * max(x1 - x0, y1 - y0)
    for px, py, nx, ny in scene2d["halfplanes"]:
        n = math.hypot(nx, ny)
        nx, ny = nx / n, ny / n
        tx, ty = -ny, nx  # along the boundary
        corners = [(px + far * tx, py + far * ty), (px - far * tx, py - far * ty),
                   (px - far * tx - far * nx, py - far * ty - far * ny),
                   (px + far * tx - far * nx, py + far * ty - far * ny)]
        ax.add_patch(Polygon(corners, closed=True, facecolor="#d9d9d9", edgecolor="#7f7f7f",
                             linewidth=0.8, zorder=1))
    patches = []
    edge_radii = scene2d["edge_radii"]
    for e, (i, j) in enumerate(edges):
        r = edge_radii[e] if e < len(edge_radii) else 0.015
        (ax_, ay), (bx, by) = vertices[i][:2], vertices[j][:2]
        length = math.hypot(bx - ax_, by - ay)
        if length > 0:
            ox, oy = -(by - ay) / length * r, (bx - ax_) / length * r
            patches.append(Polygon([(ax_ + ox, ay + oy), (bx + ox, by + oy),
                                    (bx - ox, by - oy), (ax_ - ox, ay - oy)], closed=True))
        patches += [Circle((ax_, ay), r), Circle((bx, by), r)]
    radii = scene2d["radii"]
    patches += [Circle((v[0], v[1]), radii[p] if p < len(radii) else 0.1)
                for p, v in enumerate(vertices)]
    ax.add_collection(PatchCollection(patches, facecolor=colour, edgecolor="none", alpha=0.55,
                                      zorder=2))


def draw_2d(ax, runs, index, limits, title, labels, trails, scene2d=None):
    """Frame `index` of every run, overlaid; trails of the moving points up to it; with scene2d
    (read_scene_2d), the radii and half-planes."""
    ax.cla()
    for r, frames in enumerate(runs):
        colour = COLOURS[r % len(COLOURS)]
        k = min(index, len(frames) - 1)
        vertices, _, edges = frames[k]
        if scene2d:
            draw_scene_2d(ax, scene2d, vertices, edges, limits, colour)
        if trails and k > 0:
            for p in range(len(vertices)):
                path = [frames[f][0][p] for f in range(k + 1)]
                if path[0] != path[-1] or any(q != path[0] for q in path):
                    ax.plot([q[0] for q in path], [q[1] for q in path], color=colour,
                            linewidth=0.7, alpha=0.5)
        if edges:
            ax.add_collection(LineCollection(
                [((vertices[i][0], vertices[i][1]), (vertices[j][0], vertices[j][1]))
                 for i, j in edges], colors=colour, linewidths=1.0))
        ax.scatter([v[0] for v in vertices], [v[1] for v in vertices], s=9, color=colour,
                   zorder=3, label=labels[r] if labels and r < len(labels) else None)
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_aspect("equal")
    ax.tick_params(labelsize=7)
    ax.set_title(title, fontsize=9)
    if labels:
        ax.legend(fontsize=7, loc="upper right")


def plot_lengths(path, frames, frame_time):
    """Every edge's length against time, one line per edge."""
    vertices, _, edges = frames[0]
    if not edges:
        sys.exit("render.py: --lengths needs frames with edges")
    times = [k * frame_time for k in range(len(frames))]
    fig, ax = plt.subplots(figsize=(6, 3.2))
    cmap = plt.get_cmap("viridis")
    for e, (i, j) in enumerate(edges):
        lengths = []
        for vertices, _, _ in frames:
            a, b = vertices[i], vertices[j]
            lengths.append(sum((a[c] - b[c]) ** 2 for c in range(3)) ** 0.5)
        ax.plot(times, lengths, color=cmap(e / max(len(edges) - 1, 1)), linewidth=1,
                label=f"edge {e}")
    ax.set_xlabel("t [s]" if frame_time != 1 else "frame")
    ax.set_ylabel("length [m]")
    if len(edges) <= 12:
        ax.legend(fontsize=6, ncol=2, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print(f"render.py: wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("frames", type=pathlib.Path, nargs="+",
                        help="folder(s) of frame_*.obj files")
    parser.add_argument("--png", type=pathlib.Path, help="write a strip of frames here")
    parser.add_argument("--gif", type=pathlib.Path, help="write an animation here")
    parser.add_argument("--panels", type=int, default=4, help="frames in the PNG strip (4)")
    parser.add_argument("--fps", type=int, default=10, help="GIF frames per second (10)")
    parser.add_argument("--labels", help="comma-separated names of the runs (2D overlays)")
    parser.add_argument("--trails", action="store_true", help="2D: draw the paths so far")
    parser.add_argument("--lengths", type=pathlib.Path,
                        help="plot edge lengths against time here (first run)")
    parser.add_argument("--frame-time", type=float, default=1.0,
                        help="seconds between frames, for --lengths and 2D titles (default 1: "
                             "frame numbers)")
    parser.add_argument("--dt", type=float,
                        help="the time step [s]: frame_NNNNN.obj is at t = NNNNN x dt; titles "
                             "give the time in seconds")
    parser.add_argument("--until", type=float,
                        help="with --dt: spread the PNG's panels over 0..UNTIL s (default: the "
                             "whole run)")
    parser.add_argument("--size", type=float, default=3.2, help="panel size in inches (3.2)")
    parser.add_argument("--scene", type=pathlib.Path,
                        help="3D: draw this JSON scene's colliders (moved to each frame's time "
                             "with --dt); 2D: this XML scene's radii and half-planes")
    args = parser.parse_args()
    xml_scene = args.scene is not None and args.scene.suffix.lower() == ".xml"
    scene2d = read_scene_2d(args.scene) if xml_scene else None
    colliders = read_colliders(args.scene) if args.scene and not xml_scene else ()

    runs, names = [], []
    for folder in args.frames:
        files = sorted(folder.glob("frame_*.obj"))
        if not files:
            sys.exit(f"render.py: no frame_*.obj files in {folder}")
        runs.append([read_obj(f) for f in files])
        names.append([f.stem for f in files])
    labels = args.labels.split(",") if args.labels else None
    flat = is_flat(runs)
    if len(runs) > 1 and not flat:
        sys.exit("render.py: several frame folders are overlaid in 2D scenes only")
    frames, files = runs[0], names[0]
    count_all = max(len(r) for r in runs)

    numbers = [int(f.split("_")[1]) for f in files]
    if args.until is not None and args.dt is None:
        sys.exit("render.py: --until needs --dt")

    def title(k):
        if args.dt is not None:
            return f"t = {numbers[min(k, len(numbers) - 1)] * args.dt:.2f} s"
        if args.frame_time != 1:
            return f"t = {k * args.frame_time:.2f} s"
        return files[min(k, len(files) - 1)]

    def time(k):  # seconds, for moving colliders (0 without --dt)
        return numbers[min(k, len(numbers) - 1)] * args.dt if args.dt is not None else 0.0

    if args.lengths:
        plot_lengths(args.lengths, frames, args.frame_time)
    if flat:
        limits = bounds_2d(runs, scene2d)
        if args.png:
            count = max(1, min(args.panels, count_all))
            picks = [round(k * (count_all - 1) / max(count - 1, 1)) for k in range(count)]
            fig, axes = plt.subplots(1, count, figsize=(args.size * count, args.size),
                                     squeeze=False)
            for panel, index in enumerate(picks):
                draw_2d(axes[0][panel], runs, index, limits, title(index),
                        labels if panel == 0 else None, args.trails, scene2d)
            fig.tight_layout()
            fig.savefig(args.png, dpi=90)
            plt.close(fig)
            print(f"render.py: wrote {args.png}")
        if args.gif:
            fig, ax = plt.subplots(figsize=(args.size * 1.25, args.size * 1.25))
            movie = animation.FuncAnimation(
                fig, lambda k: draw_2d(ax, runs, k, limits, title(k), labels, args.trails,
                                       scene2d),
                frames=count_all)
            movie.save(args.gif, writer=animation.PillowWriter(fps=args.fps))
            plt.close(fig)
            print(f"render.py: wrote {args.gif}")
        return

    limits = bounds(frames)
    pinned = fixed_points(frames)
    if args.png:
        picks = panel_picks(numbers, args.panels, args.dt, args.until)
        count = len(picks)
        fig = plt.figure(figsize=(args.size * count, args.size * 1.1))
        for panel, index in enumerate(picks):
            ax = fig.add_subplot(1, count, panel + 1, projection="3d")
            draw(ax, frames[index], limits, title(index), pinned, legend=panel == 0,
                 colliders=colliders, t=time(index))
        fig.subplots_adjust(left=0.01, right=0.97, bottom=0.04, top=0.93, wspace=0.08)
        fig.savefig(args.png, dpi=110)
        plt.close(fig)
        print(f"render.py: wrote {args.png}")
    if args.gif:
        fig = plt.figure(figsize=(4.5, 4))
        ax = fig.add_subplot(projection="3d")
        movie = animation.FuncAnimation(
            fig, lambda k: draw(ax, frames[k], limits, title(k), pinned, legend=True,
                                colliders=colliders, t=time(k)),
            frames=len(frames))
        movie.save(args.gif, writer=animation.PillowWriter(fps=args.fps))
        plt.close(fig)
        print(f"render.py: wrote {args.gif}")


if __name__ == "__main__":
    main()
