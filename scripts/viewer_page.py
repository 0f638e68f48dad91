#!/usr/bin/env python3
"""write_page(): the page massspring-simulate --html writes, from a trajectory array in Python (a
run of the Python module, a sweep's results). The same template (tools/simulate/viewer.html)
and the same three.js (Debian's libjs-three), so the page plays the same way.

    import sys; sys.path.insert(0, "scripts")
    from viewer_page import write_page
    write_page("run.html", positions, times, springs=sys.springs, rest_lengths=sys.rest_lengths,
               faces=faces, pinned=sys.pinned)

As a program it rewrites a trajectory CSV of massspring-simulate (--csv) as a page; springs and
faces then come from an OBJ with the run's points in order (e.g. the --pc2 rest mesh):

    viewer_page.py run.csv --obj run.obj --dt 0.005 --html run.html

Standard library only (numpy arrays are accepted wherever a list is)."""

import argparse
import base64
import json
import os
import struct
import sys
import zlib

THREE = "/usr/share/javascript/three/three.min.js"
ORBIT = "/usr/share/javascript/three/examples/js/controls/OrbitControls.js"
TEMPLATE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "simulate",
                        "viewer.html")


def _b64(fmt, values):
    return base64.b64encode(struct.pack("<%d%s" % (len(values), fmt), *values)).decode()


def write_page(path, positions, times, springs=(), rest_lengths=None, faces=(), pinned=(),
               name="massspring run", frames=None, colliders=()):
    """Writes the page of a run.

    positions     F x n x 3 positions [m] (F frames of n points), stored as float32
    times         F times [s]
    springs       m x 2 point indices; rest_lengths: m [m] (default: the lengths at frame 0)
    faces         polygons (lists of 3 or more point indices)
    pinned        pinned point indices (marked)
    frames        F frame numbers (default 0 .. F-1)
    colliders     dicts as the page reads them (viewer.html), e.g. {"shape": "sphere", "radius":
                  0.3, "poses": [[1, 0, 0, 0, 1, 0, 0, 0, 1, x, y, z]]} (one pose: it stays)
    Raises ValueError for inconsistent sizes, OSError when three.js is not installed."""
    positions = [[[float(c) for c in p] for p in frame] for frame in positions]
    count = len(positions)
    n = len(positions[0]) if count else 0
    if count == 0 or n == 0 or any(len(f) != n or any(len(p) != 3 for p in f) for f in positions):
        raise ValueError("positions: expected F x n x 3 with F, n >= 1")
    times = [float(t) for t in times]
    if len(times) != count:
        raise ValueError(f"times: {len(times)} values for {count} frames")
    springs = [(int(a), int(b)) for a, b in springs]
    if rest_lengths is None:
        x = positions[0]
        rest_lengths = [sum((x[a][c] - x[b][c]) ** 2 for c in range(3)) ** 0.5 for a, b in springs]
    rest_lengths = [float(r) for r in rest_lengths]
    if len(rest_lengths) != len(springs):
        raise ValueError(f"rest_lengths: {len(rest_lengths)} values for {len(springs)} springs")
    offsets, corners = ([0] if faces else []), []
    for face in faces:
        corners.extend(int(i) for i in face)
        offsets.append(len(corners))
    data = {"name": name, "points": n, "deflated": True,
            "springs": _b64("I", [i for s in springs for i in s]),
            "rest_lengths": _b64("f", rest_lengths),
            "face_offsets": _b64("I", offsets), "face_points": _b64("I", corners),
            "pinned": _b64("I", [int(i) for i in pinned]),
            "frames": [int(f) for f in frames] if frames is not None else list(range(count)),
            "times": times, "rest_scale": [1.0] * count, "colliders": list(colliders)}
    raw = b"".join(struct.pack("<%df" % (3 * n), *[c for p in frame for c in p])
                   for frame in positions)
    with open(TEMPLATE, encoding="utf-8") as handle:
        page = handle.read()
    with open(THREE, encoding="utf-8") as handle:
        three = handle.read()
    with open(ORBIT, encoding="utf-8") as handle:
        orbit = handle.read()
    parts = {"@@THREE@@": three, "@@ORBIT@@": orbit,
             "@@DATA@@": json.dumps(data).replace("</", "<\\/"),
             "@@POSITIONS@@": base64.b64encode(zlib.compress(raw, 1)).decode()}
    for marker, text in parts.items():
        before, found, after = page.partition(marker)
        if not found:
            raise ValueError(f"{TEMPLATE}: no {marker}")
        page = before + text + after
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(page)


def read_obj(path):
    """Springs (the `f i j` and polygon edges, each once) and polygons of an OBJ file."""
    springs, faces, seen = [], [], set()
    with open(path) as handle:
        for line in handle:
            words = line.split()
            if not words or words[0] not in ("f", "l"):
                continue
            idx = [int(w.split("/")[0]) - 1 for w in words[1:]]
            if words[0] == "f" and len(idx) >= 3:
                faces.append(idx)
                pairs = [(idx[k], idx[(k + 1) % len(idx)]) for k in range(len(idx))]
            else:
                pairs = list(zip(idx, idx[1:]))
            for a, b in pairs:
                if (min(a, b), max(a, b)) not in seen:
                    seen.add((min(a, b), max(a, b)))
                    springs.append((a, b))
    return springs, faces


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv", help="trajectory CSV of massspring-simulate --csv")
    parser.add_argument("--obj", help="OBJ with the run's points in order (springs, faces)")
    parser.add_argument("--dt", type=float, required=True, help="time step [s] (frame x dt)")
    parser.add_argument("--html", required=True, help="page to write (must not exist)")
    args = parser.parse_args()
    if os.path.exists(args.html):
        sys.exit(f"viewer_page.py: {args.html} exists; choose another name")
    frames = {}
    with open(args.csv) as handle:
        next(handle)
        for line in handle:
            row = line.split(",")
            frames.setdefault(int(row[0]), []).append([float(v) for v in row[2:5]])
    order = sorted(frames)
    springs, faces = read_obj(args.obj) if args.obj else ([], [])
    write_page(args.html, [frames[f] for f in order], [f * args.dt for f in order], springs,
               faces=faces, frames=order, name=os.path.basename(args.csv))


if __name__ == "__main__":
    main()
