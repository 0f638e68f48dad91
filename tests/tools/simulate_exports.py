#!/usr/bin/env python3
"""massspring-simulate's exports read back by readers that are not ours, compared with the CSV the
same run writes (17 significant digits: every double exactly). Run by ctest as

    simulate_exports.py MASSSPRING_SIMULATE SOURCE_DIR WORK_DIR CASE

CASE is one of
  pc2   --pc2: the header (magic, version 1, points, start frame, sample rate, samples) read with
        struct; every sample is float32(the CSV's position) bit for bit; the rest mesh OBJ has the
        points of the first frame in order; a resumed run starts at its frame; --precision float
  vtk   --vtk: every .vtu read by meshio (python3-meshio): points and velocities equal to the CSV's
        bit for bit, strain |l/l0 - 1| per spring and the mean per face, the pinned points, the
        cell types; run.pvd lists every frame with its time [s]; a second run into the folder is
        refused, or with --overwrite leaves only its own files
  page  --html: the page holds three.js and nothing from elsewhere (no src or href to a file or a
        URL); its positions (base64, deflated float32) are float32(the CSV's) bit for bit; its
        frames and times; a moving collider's pose per frame; scripts/viewer_page.py's
        write_page() writes the same data from arrays; an 81 x 81 cloth over 300 steps stays
        under 30 MB
vtk is skipped (exit 77) when numpy or meshio is missing (Debian's python3-numpy, python3-meshio);
the others need only the standard library."""

import base64
import csv
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ElementTree
import zlib

from checks import check, fail, skip


def run(simulate, args, cwd):
    result = subprocess.run([simulate] + args, cwd=cwd, capture_output=True, text=True,
                            timeout=600)
    check(result.returncode == 0,
          f"massspring-simulate {' '.join(args)}: exit {result.returncode}\n{result.stderr}")
    return result


def prepare(source, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for name in ("chain.json", "chain.obj", "drape.json", "drape.obj"):
        shutil.copy(os.path.join(source, "examples", "scenes", name), work)
    shutil.copy(os.path.join(source, "examples", "scenes_xml", "cantilever.xml"), work)


def read_csv(path):
    """{frame: (positions [n][3], velocities [n][3])} with the values as Python floats."""
    frames = {}
    with open(path) as handle:
        rows = csv.reader(handle)
        check(next(rows) == ["frame", "point", "x", "y", "z", "vx", "vy", "vz"], "CSV header")
        for row in rows:
            frame, point = int(row[0]), int(row[1])
            x, v = frames.setdefault(frame, ([], []))
            check(point == len(x), f"CSV frame {frame}: point {point} out of order")
            x.append([float(s) for s in row[2:5]])
            v.append([float(s) for s in row[5:8]])
    return frames


def float32_bits(value):
    return struct.pack("<f", value)


def pc2(simulate, source, work):
    prepare(source, work)
    run(simulate, ["drape.json", "--steps", "14", "--every", "4", "--csv", "run.csv", "--pc2",
                   "run.pc2", "--quiet"], work)
    frames = read_csv(os.path.join(work, "run.csv"))
    check(sorted(frames) == [0, 4, 8, 12, 14], f"CSV frames {sorted(frames)}")

    def read_pc2(path):
        with open(path, "rb") as handle:
            data = handle.read()
        magic, version, points, start, rate, samples = struct.unpack("<12siiffi", data[:32])
        check(magic == b"POINTCACHE2\0", f"{path}: magic {magic!r}")
        check(version == 1, f"{path}: version {version}")
        check(len(data) == 32 + points * samples * 12,
              f"{path}: {len(data)} bytes for {points} points x {samples} samples")
        return points, start, rate, samples, data[32:]

    points, start, rate, samples, body = read_pc2(os.path.join(work, "run.pc2"))
    n = len(frames[0][0])
    check((points, start, rate, samples) == (n, 0.0, 4.0, 5),
          f"header: points {points}, start {start}, rate {rate}, samples {samples}; expected "
          f"{n}, 0, 4, 5")
    for s, frame in enumerate(sorted(frames)):
        for i, x in enumerate(frames[frame][0]):
            at = (s * n + i) * 12
            expected = b"".join(float32_bits(c) for c in x)
            check(body[at:at + 12] == expected,
                  f"sample {s} (frame {frame}) point {i}: {struct.unpack('<3f', body[at:at + 12])}"
                  f" != float32 of {x}")
    # The rest mesh: the first frame's points, in order, and the scene's faces.
    vertices, faces = [], 0
    with open(os.path.join(work, "run.obj")) as handle:
        for line in handle:
            words = line.split()
            if words and words[0] == "v":
                vertices.append([float(w) for w in words[1:4]])
            faces += bool(words) and words[0] == "f"
    check(vertices == frames[0][0], "run.obj: its vertices are not the first frame's positions")
    check(faces > 0, "run.obj: no faces")

    # A run resumed from a saved state starts at its frame; --precision float.
    run(simulate, ["chain.json", "--steps", "5", "--save-state", "s.json", "--quiet"], work)
    run(simulate, ["s.json", "--steps", "3", "--csv", "r.csv", "--pc2", "r.pc2", "--quiet"], work)
    points, start, rate, samples, body = read_pc2(os.path.join(work, "r.pc2"))
    check((start, rate, samples) == (5.0, 1.0, 4), f"resumed: start {start}, rate {rate}, "
                                                   f"samples {samples}; expected 5, 1, 4")
    run(simulate, ["chain.json", "--steps", "6", "--every", "3", "--precision", "float", "--csv",
                   "f.csv", "--pc2", "f.pc2", "--quiet"], work)
    frames = read_csv(os.path.join(work, "f.csv"))
    points, start, rate, samples, body = read_pc2(os.path.join(work, "f.pc2"))
    expected = b"".join(float32_bits(c) for frame in sorted(frames) for x in frames[frame][0]
                        for c in x)
    check(body == expected, "--precision float: the samples differ from the CSV")
    shutil.rmtree(work, ignore_errors=True)
    print(f"OK: PC2 header and {5 * n} positions bit for bit (float32 of the CSV), rest mesh, "
          "resumed start frame, --precision float")


def vtk(simulate, source, work):
    try:
        import meshio
        import numpy as np
    except ImportError as error:
        skip(f"{error} (Debian: python3-meshio, python3-numpy)")
    prepare(source, work)
    checked = 0
    for scene, args in (("drape.json", ["--steps", "10", "--every", "5"]),
                        ("chain.json", ["--steps", "6", "--every", "3"]),
                        ("cantilever.xml", ["--steps", "40", "--every", "20"])):
        stem = scene.split(".")[0]
        state = [] if scene.endswith(".xml") else ["--save-state", stem + "_state.json"]
        run(simulate, [scene] + args + ["--csv", stem + ".csv", "--vtk", stem, "--quiet"] + state,
            work)
        frames = read_csv(os.path.join(work, stem + ".csv"))
        folder = os.path.join(work, stem)
        pvd = ElementTree.parse(os.path.join(folder, "run.pvd")).getroot()
        sets = pvd.findall("./Collection/DataSet")
        check([d.get("file") for d in sets] == [f"frame_{f:05d}.vtu" for f in sorted(frames)],
              f"{stem}/run.pvd lists {[d.get('file') for d in sets]}")
        rest = None
        for d in sets:
            frame = int(d.get("file")[6:11])
            mesh = meshio.read(os.path.join(folder, d.get("file")))
            x = np.array(frames[frame][0])
            v = np.array(frames[frame][1])
            check(mesh.points.dtype == np.float64 and np.array_equal(mesh.points, x),
                  f"{stem} frame {frame}: points differ from the CSV")
            check(np.array_equal(mesh.point_data["velocity"], v),
                  f"{stem} frame {frame}: velocities differ from the CSV")
            lines = np.concatenate([b.data for b in mesh.cells if b.type == "line"])
            strain = np.concatenate([s for b, s in zip(mesh.cells, mesh.cell_data["strain"])
                                     if b.type == "line"])
            length = np.linalg.norm(x[lines[:, 0]] - x[lines[:, 1]], axis=1)
            if rest is None and scene.endswith(".xml"):  # <springforce l0>, in file order
                root = ElementTree.parse(os.path.join(work, scene)).getroot()
                rest = np.array([float(e.get("l0")) for e in root.iter("springforce")])
            if rest is None:  # a JSON scene: the rest lengths are the lengths at frame 0
                rest = length
                check(np.all(strain < 1e-12), f"{stem} frame 0: strain {strain.max()} at rest")
            check(np.allclose(strain, np.abs(length / rest - 1), rtol=1e-12, atol=1e-15),
                  f"{stem} frame {frame}: strain is not |l/l0 - 1|")
            # faces: the mean strain of the springs along their boundary
            spring_of = {tuple(sorted(e)): k for k, e in enumerate(lines.tolist())}
            for b, s in zip(mesh.cells, mesh.cell_data["strain"]):
                if b.type == "line":
                    continue
                for face, value in zip(b.data.tolist(), s):
                    on = [spring_of[key] for key in
                          (tuple(sorted((face[k], face[(k + 1) % len(face)])))
                           for k in range(len(face))) if key in spring_of]
                    mean = float(np.mean(strain[on])) if on else 0.0
                    check(abs(value - mean) <= 1e-12 * max(1.0, mean),
                          f"{stem} frame {frame}: face strain {value}, mean of its springs {mean}")
            checked += 1
        if scene != "cantilever.xml":
            with open(os.path.join(work, stem + "_state.json")) as handle:
                pinned = sorted(json.load(handle).get("pinned", []))
            marked = sorted(np.nonzero(mesh.point_data["pinned"])[0].tolist())
            check(marked == pinned, f"{stem}: pinned {marked}, the state says {pinned}")
        faces = sum(len(b.data) for b in mesh.cells if b.type != "line")
        check((faces > 0) == (stem == "drape"), f"{stem}: {faces} faces")
    # --overwrite: a second run into the same folder leaves only its own files (never mixed);
    # without --overwrite it is refused and nothing changes.
    before = sorted(os.listdir(os.path.join(work, "chain")))
    result = subprocess.run([simulate, "chain.json", "--steps", "2", "--vtk", "chain"], cwd=work,
                            capture_output=True, text=True)
    check(result.returncode == 1 and "give --overwrite" in result.stderr and
          sorted(os.listdir(os.path.join(work, "chain"))) == before,
          f"a second --vtk run without --overwrite: exit {result.returncode} {result.stderr}")
    run(simulate, ["chain.json", "--steps", "2", "--vtk", "chain", "--overwrite", "--quiet"], work)
    after = sorted(os.listdir(os.path.join(work, "chain")))
    check(after == ["frame_00000.vtu", "frame_00001.vtu", "frame_00002.vtu", "run.pvd"],
          f"--vtk --overwrite: {after}")
    # times: frame x dt (drape's dt is 0.005 s)
    pvd = ElementTree.parse(os.path.join(work, "drape", "run.pvd")).getroot()
    times = [float(d.get("timestep")) for d in pvd.findall("./Collection/DataSet")]
    check(times == [0.0, 5 * 0.005, 10 * 0.005], f"drape/run.pvd times {times}")
    shutil.rmtree(work, ignore_errors=True)
    print(f"OK: {checked} VTK frames read by meshio equal the CSV bit for bit, strain per spring "
          "and face, pins, the time series")


def page_data(path):
    """The description and the float32 positions (bytes) a page holds."""
    with open(path, encoding="utf-8") as handle:
        text = handle.read()
    data = re.search(r'<script id="massspring-data" type="application/json">\s*(.*?)\s*</script>',
                     text, re.S)
    positions = re.search(r'<script id="massspring-positions" type="application/octet-stream">'
                          r'\s*(.*?)\s*</script>', text, re.S)
    check(data and positions, f"{path}: no data or positions element")
    meta = json.loads(data.group(1))
    raw = base64.b64decode(positions.group(1), validate=True)
    if meta.get("deflated"):
        raw = zlib.decompress(raw)
    return text, meta, raw


def page(simulate, source, work):
    prepare(source, work)
    run(simulate, ["drape.json", "--steps", "14", "--every", "4", "--csv", "run.csv", "--html",
                   "run.html", "--quiet"], work)
    text, meta, raw = page_data(os.path.join(work, "run.html"))
    frames = read_csv(os.path.join(work, "run.csv"))
    check(meta["frames"] == sorted(frames), f"page frames {meta['frames']}")
    check(meta["times"] == [f * 0.005 for f in sorted(frames)], f"page times {meta['times']}")
    expected = b"".join(float32_bits(c) for frame in sorted(frames) for x in frames[frame][0]
                        for c in x)
    check(raw == expected, "the page's positions are not float32 of the CSV's")
    check([c["shape"] for c in meta["colliders"]] == ["plane", "sphere"],
          f"colliders {[c['shape'] for c in meta['colliders']]}")
    check(all(len(c["poses"]) == len(frames) for c in meta["colliders"]), "a pose per frame")
    check("three.js" in text.lower() or "REVISION" in text, "three.js is not in the page")
    check("OrbitControls" in text, "OrbitControls is not in the page")
    # Self-contained: no element loads anything (src=, href= to a file or URL, @import, url()).
    for pattern in (r'<(?:script|img|link|iframe)[^>]*\s(?:src|href)\s*=', r"@import",
                    r"url\(\s*['\"]?(?:https?:|file:|//)"):
        found = re.search(pattern, text)
        check(not found, f"the page loads something: {found.group(0) if found else ''}")

    # A moving collider: its pose per frame is where it was (t = t0 + v time, R turning).
    with open(os.path.join(work, "moving.json"), "w") as handle:
        json.dump({"obj": "chain.obj", "b": [1], "k": 10, "m": 1, "dt": 0.01,
                   "colliders": [{"type": "box", "center": [5, 0, 0], "half_extents": [1, 1, 1],
                                  "velocity": [0, 0, 2], "angular_velocity": [0, 3, 0]}]},
                  handle)
    run(simulate, ["moving.json", "--steps", "4", "--html", "moving.html", "--quiet"], work)
    _, moving, _ = page_data(os.path.join(work, "moving.html"))
    poses = moving["colliders"][0]["poses"]
    check(len(poses) == 5, f"moving: {len(poses)} poses for 5 frames")
    import math
    for k, pose in enumerate(poses):
        angle = 3 * 0.01 * k  # about y: R = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
        expected = [math.cos(angle), 0, math.sin(angle), 0, 1, 0, -math.sin(angle), 0,
                    math.cos(angle), 5, 0, 2 * 0.01 * k]
        check(all(abs(a - b) <= 1e-12 for a, b in zip(pose, expected)),
              f"moving: frame {k}: pose {pose}, expected {expected}")

    # scripts/viewer_page.py writes the same page from arrays: the same data, given the same
    # springs, rest lengths and faces.
    sys.path.insert(0, os.path.join(source, "scripts"))
    import viewer_page

    def unpack(fmt, b64):
        raw = base64.b64decode(b64)
        return list(struct.unpack("<%d%s" % (len(raw) // 4, fmt), raw))
    pairs = unpack("I", meta["springs"])
    offsets, corners = unpack("I", meta["face_offsets"]), unpack("I", meta["face_points"])
    order = sorted(frames)
    viewer_page.write_page(os.path.join(work, "py.html"), [frames[f][0] for f in order],
                           [f * 0.005 for f in order], springs=list(zip(pairs[::2], pairs[1::2])),
                           rest_lengths=unpack("f", meta["rest_lengths"]),
                           faces=[corners[a:b] for a, b in zip(offsets, offsets[1:])],
                           frames=order, name=meta["name"])
    _, meta_py, raw_py = page_data(os.path.join(work, "py.html"))
    check(raw_py == raw, "viewer_page.write_page: positions differ from the tool's page")
    for key in ("springs", "rest_lengths", "face_offsets", "face_points", "frames", "times"):
        check(meta_py[key] == meta[key], f"viewer_page.write_page: {key} differs")

    # 81 x 81 points, 300 steps, every frame written: the page stays under 30 MB.
    run(simulate, ["--generate", "cloth:81x81", "--steps", "300", "--iterations", "2", "--html",
                   "big.html", "--quiet"], work)
    size = os.path.getsize(os.path.join(work, "big.html"))
    check(size < 30e6, f"81 x 81 over 301 frames: {size} bytes, expected under 30 MB")
    shutil.rmtree(work, ignore_errors=True)
    print(f"OK: the page holds float32 of the CSV bit for bit, its frames, times and colliders, "
          f"nothing from elsewhere; 81 x 81 x 301 frames: {size / 1e6:.1f} MB")


def main():
    simulate, source, work, case = sys.argv[1:5]
    simulate = os.path.abspath(simulate)
    {"pc2": pc2, "vtk": vtk, "page": page}[case](simulate, source, work)


if __name__ == "__main__":
    main()
