#!/usr/bin/env python3
"""massspring-simulate loses nothing: run by ctest (tests/CMakeLists.txt) as

    simulate_signals.py MASSSPRING_SIMULATE WORK_DIR CASE

CASE is one of
  sigint      SIGINT during a long run: exit 130, "interrupted at frame N; frames 0..N written",
              frames 0..N all there and whole, the CSV holds exactly frames 0..N, no .tmp file;
  sigterm     the same with SIGTERM (exit 143 = 128 + 15) and --every 7: the multiples of 7 and
              the last frame N;
  diverge     forward Euler with a step far too large: exit 2, "step K: ... non-finite", frames
              0..K-1 all there and whole, none after, CSV closed, no .tmp file.
Only the standard library; no timing assertion (the signal is sent once frames appear)."""

import os
import re
import shutil
import signal
import subprocess
import sys
import time

from checks import check, fail


def read_obj(path, points):
    """Parses a frame completely: `points` finite vertices, faces within range, ends in a newline."""
    with open(path, "rb") as f:
        data = f.read()
    check(data.endswith(b"\n"), f"{path}: does not end with a newline (truncated?)")
    vertices = 0
    faces = 0
    for number, line in enumerate(data.decode("ascii").splitlines(), 1):
        tokens = line.split()
        if not tokens or tokens[0] == "#":
            continue
        if tokens[0] == "v":
            check(len(tokens) == 4, f"{path}:{number}: vertex line {line!r}")
            values = [float(t) for t in tokens[1:]]
            check(all(abs(x) < float("inf") for x in values), f"{path}:{number}: not finite")
            vertices += 1
        elif tokens[0] == "f":
            check(len(tokens) >= 3, f"{path}:{number}: face line {line!r}")
            check(all(1 <= int(t) <= points for t in tokens[1:]), f"{path}:{number}: index")
            faces += 1
        else:
            fail(f"{path}:{number}: unexpected line {line!r}")
    check(vertices == points, f"{path}: {vertices} vertices, expected {points}")
    return faces


def frames_in(folder):
    names = sorted(os.listdir(folder))
    stray = [n for n in names if not re.fullmatch(r"frame_\d{5}\.obj", n)]
    check(not stray, f"{folder}: unexpected files {stray} (leftover temporary files?)")
    return [int(n[6:11]) for n in names]


def check_csv(path, points, frames):
    check(not os.path.exists(path + ".tmp"), f"{path}.tmp left behind")
    with open(path) as f:
        lines = f.read().splitlines()
    check(lines[0] == "frame,point,x,y,z,vx,vy,vz", f"{path}: header {lines[0]!r}")
    rows = [line.split(",") for line in lines[1:]]
    check(all(len(r) == 8 for r in rows), f"{path}: a row without 8 fields")
    written = sorted({int(r[0]) for r in rows})
    check(written == frames, f"{path}: frames {written[:3]}..{written[-3:]}, expected {frames[:3]}..{frames[-3:]}")
    check(len(rows) == points * len(frames), f"{path}: {len(rows)} rows for {len(frames)} frames")


def interrupted(simulate, work, sig, every, status):
    out, csv = os.path.join(work, "frames"), os.path.join(work, "trajectory.csv")
    columns, rows = 30, 20
    points = columns * rows
    process = subprocess.Popen(
        [simulate, "--generate", f"cloth:{columns}x{rows}", "--steps", "100000000", "--every",
         str(every), "--out", out, "--csv", csv],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # wait until a few frames exist (the run is well under way), then send the signal once
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and process.poll() is None:
        if os.path.isdir(out) and len(os.listdir(out)) >= 3:
            break
        time.sleep(0.05)
    if process.poll() is not None:
        fail(f"massspring-simulate ended early: {process.communicate()}")
    process.send_signal(sig)
    stdout, stderr = process.communicate(timeout=300)
    print(stdout, stderr, sep="")
    check(process.returncode == status, f"exit status {process.returncode}, expected {status}")
    match = re.search(r"massspring-simulate: interrupted at frame (\d+); frames 0\.\.(\d+) written",
                      stderr)
    check(match is not None and match.group(1) == match.group(2), f"message: {stderr!r}")
    last = int(match.group(1))
    expected = sorted({f for f in range(0, last + 1) if f % every == 0} | {last})
    written = frames_in(out)
    check(written == expected, f"frames {written[:3]}..{written[-3:]}, expected 0..{last} every {every}")
    faces = {read_obj(os.path.join(out, f"frame_{f:05d}.obj"), points) for f in written}
    check(len(faces) == 1, f"frames differ in their face counts: {faces}")
    check_csv(csv, points, expected)
    print(f"OK: interrupted at frame {last}; {len(written)} whole frames")


def diverge(simulate, work):
    out, csv = os.path.join(work, "frames"), os.path.join(work, "trajectory.csv")
    points = 10
    result = subprocess.run(
        [simulate, "--generate", f"chain:{points}", "--integrator", "forward-euler", "--dt", "1",
         "--frames", "100000", "--out", out, "--csv", csv],
        capture_output=True, text=True, timeout=300)
    print(result.stdout, result.stderr, sep="")
    check(result.returncode == 2, f"exit status {result.returncode}, expected 2")
    # Either check may stop it first: the energy guard or a non-finite value.
    match = re.search(r"massspring-simulate: step (\d+): (?:the step produced a non-finite state|"
                      r"the total energy passed the divergence limit \([^)]*\), or the step gained more "
                      r"than [0-9.e+]+ x the scale, the integrator's own bound); "
                      r"stopped with the last (?:finite|good) state \(steps 0\.\.(\d+) written\)",
                      result.stderr)
    check(match is not None, f"message: {result.stderr!r}")
    bad, last = int(match.group(1)), int(match.group(2))
    check(last == bad - 1 and last > 0, f"step {bad}, last written {last}")
    written = frames_in(out)
    check(written == list(range(0, last + 1)), f"frames {written[:3]}..{written[-3:]}, expected 0..{last}")
    for f in written:
        read_obj(os.path.join(out, f"frame_{f:05d}.obj"), points)
    check_csv(csv, points, written)
    print(f"OK: diverged at step {bad}; frames 0..{last} kept, whole")


def main():
    if len(sys.argv) != 4:
        fail(__doc__)
    simulate, work, case = sys.argv[1:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    if case == "sigint":
        interrupted(simulate, work, signal.SIGINT, 1, 130)
    elif case == "sigterm":
        interrupted(simulate, work, signal.SIGTERM, 7, 143)
    elif case == "diverge":
        diverge(simulate, work)
    else:
        fail(f"unknown case {case}")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
