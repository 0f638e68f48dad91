#!/usr/bin/env python3
"""scripts/render.py draws the motion (the demo picture): run by ctest as

    render_demo.py MASSSPRING_SIMULATE SOURCE_DIR WORK_DIR

A 6x5 cloth runs 45 frames (dt = 1/30 s, every 3rd written) and saves its state. Then:
- fixed_points() finds exactly the pinned points the saved state lists;
- panel_picks() with --dt 1/30 --until 1 and 6 panels shows t = 0, 0.2, ..., 1.0 s (the first
  second), not frames spread over the whole run;
- draw() titles a panel with the time in seconds, labels the axes in metres and marks the pins;
- render.py --png with those options writes a PNG.
Exits 77 (skipped) when matplotlib is missing."""

import json
import os
import shutil
import subprocess
import sys


def check(condition, message):
    if not condition:
        print("FAIL: " + message)
        sys.exit(1)


def main():
    simulate, source, work = sys.argv[1:4]
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("matplotlib missing: skipped")
        sys.exit(77)
    sys.path.insert(0, os.path.join(source, "scripts"))
    import render  # noqa: E402

    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    frames_dir = os.path.join(work, "frames")
    state = os.path.join(work, "state.json")
    result = subprocess.run([simulate, "--generate", "cloth:6x5", "--steps", "45", "--every", "3",
                             "--out", frames_dir, "--save-state", state, "--quiet"],
                            capture_output=True, text=True)
    check(result.returncode == 0, f"simulate: {result.stderr}")
    with open(state) as f:
        pinned = json.load(f)["pinned"]
    import pathlib
    files = sorted(pathlib.Path(frames_dir).glob("frame_*.obj"))
    frames = [render.read_obj(f) for f in files]
    check(render.fixed_points(frames) == pinned,
          f"fixed points {render.fixed_points(frames)}, pinned {pinned}")

    numbers = [int(f.stem.split("_")[1]) for f in files]
    picks = render.panel_picks(numbers, 6, 1 / 30, 1.0)
    times = [round(numbers[k] / 30, 6) for k in picks]
    check(times == [0, 0.2, 0.4, 0.6, 0.8, 1.0], f"panels at t = {times}")
    whole = render.panel_picks(numbers, 4)
    check([numbers[k] for k in whole] == [0, 15, 30, 45], f"whole run: {whole}")

    import matplotlib.pyplot as plt
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    render.draw(ax, frames[-1], render.bounds(frames), "t = 1.50 s", pinned, legend=True)
    check(ax.get_title() == "t = 1.50 s", ax.get_title())
    check((ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("x [m]", "z [m]", "y [m]"),
          "axis labels")
    check(ax.get_legend_handles_labels()[1] == ["pinned"], "pins marked")
    plt.close(fig)

    png = os.path.join(work, "cloth.png")
    result = subprocess.run([sys.executable, os.path.join(source, "scripts", "render.py"),
                             frames_dir, "--dt", str(1 / 30), "--until", "1", "--panels", "6",
                             "--png", png], capture_output=True, text=True)
    check(result.returncode == 0 and os.path.getsize(png) > 10000, f"render.py: {result.stderr}")
    shutil.rmtree(work, ignore_errors=True)
    print("OK: pins found, the first second sampled in seconds, axes labelled, PNG written")


if __name__ == "__main__":
    main()
