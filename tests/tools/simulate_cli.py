#!/usr/bin/env python3
"""massspring-simulate's refusals, outputs and resume, on the real binary: run by ctest
(tests/CMakeLists.txt) as

    simulate_cli.py MASSSPRING_SIMULATE SOURCE_DIR WORK_DIR CASE

CASE is one of
  refusals   every bad input of docs/errors.md's "massspring-simulate" table: exit 1, the exact
             message (one line, prefixed "massspring-simulate: "), nothing on stdout (no run
             started), and the work folder byte for byte as it was (nothing written or removed);
             `--table` prints the table instead of checking it
  help       --help exits 0 and shows a default for every option that takes a value; --version
             prints the project's version and exits 0
  overwrite  --overwrite replaces an existing CSV and the frames of an earlier run (never mixed)
  rename     the CSV's final rename fails (its name became a folder during the run): the .tmp is
             kept, whole, and the message names it; the header line arrives while the run goes on
  killed     a SIGKILLed run leaves <csv>.tmp; the next run names it and refuses, --overwrite
             replaces it
  options    the solver options reach the solver: Chebyshev and Anderson change the trajectory,
             --threads 2 gives the same one bit for bit (where OpenMP is), --ordering and
             backward Euler's options run, the header names what runs
  length     --duration (seconds), --frames (written frames, x --every steps) and --steps set
             the run's length as documented; a JSON scene's own "dt" and "gravity" give the run of
             the same scene without them given --dt and --gravity, bit for bit
  progress   --progress prints "step K of N" lines while the run goes on (none with --quiet, none
             in a short run at the default 10 s)
  hint       an explicit integrator that diverges is told the step stable_time_step() gives, and
             a run at that step (symplectic Euler) does not diverge
  folders    every output (--out, --csv, --html, --pc2, --vtk, --save-state) creates the missing
             folders of its path, alone and all at once; --help says so
  readme     every ```sh block of README.md that runs massspring-simulate, run as printed (in a
             copy of the scenes) twice: both exit 0, and everything written is under out/
  resume     --save-state after 10 frames then 10 more from the saved state give the CSV of 20
             frames exactly (plain, Chebyshev, Anderson, backward Euler, --shrink; a scene with
             moving colliders of every kind, with every integrator; --self-collision, whose
             surface and thickness the state holds)
  work       the line on the energy the contact response added (StepReport::contact_work):
             absent for the drape, whose response only stops points, and after --quiet; present,
             with the step and the scene's energy scale, for the clothesline, whose self-collision
             pass stretches springs (docs/contact.md, Limits)
Only the standard library."""

import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

from checks import check, fail

P = "massspring-simulate: "


def snapshot(folder):
    """Every file and folder under `folder` with its bytes' hash."""
    out = {}
    for root, dirs, files in os.walk(folder):
        for d in dirs:
            out[os.path.relpath(os.path.join(root, d), folder) + "/"] = "dir"
        for f in files:
            with open(os.path.join(root, f), "rb") as handle:
                out[os.path.relpath(os.path.join(root, f), folder)] = hashlib.sha256(
                    handle.read()).hexdigest()
    return out


def run(simulate, args, cwd, timeout=600):
    return subprocess.run([simulate] + args, cwd=cwd, capture_output=True, text=True,
                          timeout=timeout)


def prepare(source, work):
    """The work folder every refusal starts from."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for name in ("chain.json", "chain.obj"):
        shutil.copy(os.path.join(source, "examples", "scenes", name), work)
    for name in ("orbit.xml", "balls_penalty.xml"):
        shutil.copy(os.path.join(source, "examples", "scenes_xml", name), work)
    os.makedirs(os.path.join(work, "adir.json"))
    os.makedirs(os.path.join(work, "stale"))
    os.makedirs(os.path.join(work, "oldvtk"))
    for f in range(3):
        with open(os.path.join(work, "stale", f"frame_{f:05d}.obj"), "w") as handle:
            handle.write("v 0 0 0\n")
    for name, text in (("oldvtk/frame_00000.vtu", "<VTKFile/>\n"),
                       ("oldvtk/run.pvd", "<VTKFile/>\n"),
                       ("old.pc2", "POINTCACHE2\n"), ("kept.obj", "v 0 0 0\n"),
                       ("existing.csv", "keep me\n"), ("t.csv.tmp", "frame,point\n0,0\n"),
                       ("file.txt", "a file\n"),
                       ("edges.json", '{"obj": "edges.obj", "b": [1], "k": 10}\n'),
                       ("bad_dt.json", '{"obj": "chain.obj", "b": [1], "k": 10, "m": 1, '
                                       '"dt": 0}\n'),
                       ("bad_gravity.json", '{"obj": "chain.obj", "b": [1], "k": 10, "m": 1, '
                                            '"gravity": [0, -9.8]}\n'),
                       ("own_gravity.json", '{"obj": "chain.obj", "b": [1], "k": 10, "m": 1, '
                                            '"gravity": [0, -1, 0], "dt": 0.01}\n'),
                       ("edges.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n")):
        with open(os.path.join(work, name), "w") as handle:
            handle.write(text)


FLOAT_OPTIONS = ["--dt", "--duration", "--progress", "--shrink", "--tolerance", "--penalty-weight", "--contact-weight",
                 "--chebyshev-rho",
                 "--chebyshev-gamma", "--newton-tolerance", "--guard-growth", "--self-collision"]

# (arguments, expected stderr after the prefix); every one exits 1 with nothing written.
REFUSALS = [
    (["chain.json", "--frames", "2", "--csv", "chain.json"],
     "--csv chain.json: is chain.json, a file this run reads; choose another name"),
    (["chain.json", "--csv", "chain.obj"],
     "--csv chain.obj: is chain.obj, a file this run reads; choose another name"),
    (["chain.json", "--save-state", "chain.json"],
     "--save-state chain.json: is chain.json, a file this run reads; choose another name"),
    (["chain.json", "--csv", "adir.json"], "--csv adir.json: is a directory; give a file name"),
    (["chain.json", "--csv", "existing.csv"],
     "--csv existing.csv: exists; give --overwrite to replace it, or choose another name"),
    (["chain.json", "--csv", "t.csv"],
     "--csv t.csv: t.csv.tmp exists, left by an earlier run that did not finish (killed?); it "
     "may hold its output: move or delete it, or give --overwrite to replace it"),
    # a missing folder is created (the folders case); a file where a folder should be is refused
    (["chain.json", "--csv", "file.txt/such/x.csv"],
     "--csv file.txt/such/x.csv: file.txt is not a folder"),
    # a refused run creates no folder for its other outputs
    (["chain.json", "--csv", "new/x.csv", "--html", "existing.csv"],
     "--html existing.csv: exists; give --overwrite to replace it, or choose another name"),
    (["chain.json", "--csv", "a.csv", "--save-state", "a.csv"],
     "--csv a.csv: another output of this run is a.csv; give each output its own file"),
    (["chain.json", "--out", "stale"],
     "--out stale: holds 3 frame files of an earlier run (frame_00000.obj ... frame_00002.obj); "
     "give --overwrite to delete them first, or choose an empty folder"),
    (["chain.json", "--out", "file.txt"], "--out file.txt: exists and is not a folder"),
    (["chain.json", "--html", "existing.csv"],
     "--html existing.csv: exists; give --overwrite to replace it, or choose another name"),
    (["chain.json", "--html", "adir.json"], "--html adir.json: is a directory; give a file name"),
    (["chain.json", "--html", "file.txt/x.html"], "--html file.txt/x.html: file.txt is not a folder"),
    (["chain.json", "--html", "chain.json"],
     "--html chain.json: is chain.json, a file this run reads; choose another name"),
    (["chain.json", "--html", "a.out", "--csv", "a.out"],
     "--csv a.out: another output of this run is a.out; give each output its own file"),
    (["chain.json", "--pc2", "run.cache"],
     "--pc2 run.cache: expected a file name ending in .pc2 (its rest mesh is written beside it, "
     "as .obj)"),
    (["chain.json", "--pc2", "old.pc2"],
     "--pc2 old.pc2: exists; give --overwrite to replace it, or choose another name"),
    (["chain.json", "--pc2", "kept.pc2"],
     "--pc2 kept.pc2: its rest mesh kept.obj: exists; give --overwrite to replace it, or choose "
     "another name"),
    (["chain.json", "--pc2", "chain.pc2"],
     "--pc2 chain.pc2: its rest mesh chain.obj: is chain.obj, a file this run reads; choose "
     "another name"),
    (["chain.json", "--pc2", "file.txt/r.pc2"], "--pc2 file.txt/r.pc2: file.txt is not a folder"),
    (["chain.json", "--out", "file.txt/f"], "--out file.txt/f: file.txt is not a folder"),
    (["chain.json", "--vtk", "file.txt/v"], "--vtk file.txt/v: file.txt is not a folder"),
    (["chain.json", "--save-state", "file.txt/s.json"],
     "--save-state file.txt/s.json: file.txt is not a folder"),
    (["chain.json", "--vtk", "file.txt"], "--vtk file.txt: exists and is not a folder"),
    (["chain.json", "--vtk", "oldvtk"],
     "--vtk oldvtk: holds 2 files of an earlier run (frame_00000.vtu ... run.pvd); give "
     "--overwrite to delete them first, or choose an empty folder"),
    (["chain.json", "--vtk", "v", "--out", "v"],
     "--vtk v: is also the --out folder; give each its own folder"),
    (["chain.json", "--vtk", "v.csv", "--csv", "v.csv"],
     "--vtk v.csv: is also the file of another output"),
    (["chain.obj"], 'chain.obj: unsupported scene format ".obj": supported are .json (JSON+OBJ '
                    'scene), .xml (FOSSSim XML scene)'),
    (["edges.json"], 'edges.json: scene has no faces to take masses from: give a mass ("m")'),
    (["none.json"], "none.json: cannot read JSON scene: no such file"),
    (["orbit.xml", "--gravity", "0,-9.8,0"],
     "--gravity: orbit.xml carries its own force terms (an XML scene); --gravity and --force "
     "apply to JSON+OBJ and generated scenes"),
    (["balls_penalty.xml", "--save-state", "s.json"],
     "--save-state s.json: balls_penalty.xml has a penalty contact term, which a state file "
     "cannot hold (it holds gravity, constant force, linear drag, gravitational attraction and "
     "vortex force)"),
    ([], "give either a scene file or --generate (see --help)"),
    (["chain.json", "--generate", "chain"], "give either a scene file or --generate (see --help)"),
    (["--generate", "blob"],
     '--generate blob: unknown generator "blob" (expected cloth, chain or net)'),
    (["--generate", "cloth:3"], "--generate cloth:3: expected cloth:COLUMNSxROWS with whole numbers"),
    (["chain.json", "--frames", "abc"], '--frames: "abc" is not an integer'),
    (["chain.json", "--frames", "1.5"], '--frames: "1.5" is not an integer'),
    (["chain.json", "--frames", "-1"], "--frames: -1 is out of range (0 to 100000000)"),
    (["chain.json", "--frames", "99999999999999999999"],
     "--frames: 99999999999999999999 is out of range (0 to 100000000)"),
    (["chain.json", "--dt", "0"], "--dt: must be > 0, got 0"),
    (["chain.json", "--dt", "-1e-3"], "--dt: must be > 0, got -1e-3"),
    (["chain.json", "--dt", "1e999"], "--dt: must be a finite number, got 1e999"),
    (["chain.json", "--dt", "fast"], '--dt: "fast" is not a number'),
    (["chain.json", "--every", "0"], "--every: 0 is out of range (1 to 100000000)"),
    (["chain.json", "--threads", "0"], "--threads: 0 is out of range (1 to 256)"),
    (["chain.json", "--iterations", "0"], "--iterations: 0 is out of range (1 to 1000000)"),
    (["chain.json", "--acceleration", "chebyshev", "--chebyshev-rho", "1"],
     "--chebyshev-rho: must be in [0, 1), got 1"),
    (["chain.json", "--acceleration", "chebyshev", "--chebyshev-gamma", "0"],
     "--chebyshev-gamma: must be in (0, 1], got 0"),
    (["chain.json", "--acceleration", "anderson", "--anderson-window", "17"],
     "--anderson-window: 17 is out of range (1 to 16)"),
    (["chain.json", "--chebyshev-rho", "0.5"],
     "--chebyshev-rho: applies to --acceleration chebyshev only (this run: fast-mass-spring, "
     "--acceleration anderson)"),
    (["chain.json", "--integrator", "symplectic-euler", "--iterations", "5"],
     "--iterations: applies to --integrator fast-mass-spring only (this run: symplectic-euler)"),
    (["chain.json", "--integrator", "forward-euler", "--contact-weight", "1"],
     "--contact-weight: applies to --integrator fast-mass-spring, backward-euler or "
     "linearized-backward-euler only (this run: forward-euler)"),
    (["chain.json", "--newton-tolerance", "1e-6"],
     "--newton-tolerance: applies to --integrator backward-euler only (this run: "
     "fast-mass-spring, --acceleration anderson)"),
    (["chain.json", "--gravity", "0,1"], "--gravity: At least 3 required but received 2 (see --help)"),
    (["chain.json", "--save-every", "5"], "--save-every 5: needs --save-state FILE"),
    (["chain.json", "--precision", "float", "--pins", "penalty"],
     "--pins penalty with --precision float: w = 10000000000 swamps the rest of Q in "
     "float; use --pins exact"),
    (["chain.json", "--storage", "dense", "--ordering", "nested-dissection"],
     "FastMassSpring: options.ordering = NestedDissection: this storage's Cholesky takes no "
     "given elimination order (use Sparse storage)"),
    (["chain.json", "--bogus"], "The following argument was not expected: --bogus (see --help)"),
    (["chain.json", "--iteration", "5"],
     "The following arguments were not expected: --iteration 5 (did you mean --iterations?) "
     "(see --help)"),
    (["chain.json", "--integrater=rk4"],
     "The following argument was not expected: --integrater=rk4 (did you mean --integrator?) "
     "(see --help)"),
    (["chain.json", "--dtt", "0.1"],
     "The following arguments were not expected: --dtt 0.1 (did you mean --dt?) (see --help)"),
    # listed in the order given
    (["chain.json", "a", "b", "--bogus", "c"],
     "The following arguments were not expected: a b --bogus c (see --help)"),
    (["chain.json", "--self"],
     "The following argument was not expected: --self (did you mean --self-collision?) "
     "(see --help)"),
    (["chain.json", "--steps", "3", "--frames", "4"],
     "--steps and --frames: give one of --steps, --frames and --duration"),
    (["chain.json", "--frames", "3", "--duration", "4"],
     "--frames and --duration: give one of --steps, --frames and --duration"),
    (["chain.json", "--steps", "-1"], "--steps: -1 is out of range (0 to 100000000)"),
    (["chain.json", "--frames", "1e3"], '--frames: "1e3" is not an integer'),
    (["chain.json", "--duration", "-1"], "--duration: must be >= 0, got -1"),
    (["chain.json", "--progress", "-1"], "--progress: must be >= 0, got -1"),
    (["chain.json", "--frames", "100000000", "--every", "2"],
     "--frames 100000000 x --every 2 = 200000000 steps: more than 10^8; ask for fewer, or a "
     "larger --dt"),
    (["chain.json", "--duration", "1e7", "--dt", "0.01"],
     "--duration 10000000 s / dt 0.01 s = 1000000000 steps: more than 10^8; ask for fewer, or a "
     "larger --dt"),
    (["bad_dt.json"], 'bad_dt.json: key "dt": expected a finite number > 0, got 0'),
    (["bad_gravity.json"],
     'bad_gravity.json: key "gravity": expected [gx, gy, gz] (three numbers, m/s^2), got '
     '[0,-9.8]'),
    (["own_gravity.json", "--gravity", "0,-9.8,0"],
     '--gravity: own_gravity.json carries its own gravity (its key "gravity"); change it there, '
     'or leave out --gravity'),
    (["chain.json", "--self-collision", "0.005"],
     "--self-collision: chain.json has no surface to collide (no polygons: chains, nets and XML "
     "scenes have none)"),
    (["--generate", "net", "--self-collision", "0.005"],
     "--self-collision: --generate net has no surface to collide (no polygons: chains, nets and "
     "XML scenes have none)"),
    (["chain.json", "--self-collision", "0"], "--self-collision: must be > 0, got 0"),
    (["chain.json", "--contact-weight", "-1"], "--contact-weight: must be >= 0, got -1"),
    (["chain.json", "--integrator", "rk5"],
     "--integrator: rk5 not in {forward-euler,symplectic-euler,backward-euler,"
     "linearized-backward-euler,fast-mass-spring} (see --help)"),
] + [(["chain.json", option, "nan"], f"{option}: must be a finite number, got nan")
     for option in FLOAT_OPTIONS] + [
    (["chain.json", "--gravity", "0,nan,0"], "--gravity: must be a finite number, got nan"),
    (["chain.json", "--force", "inf,0,0"], "--force: must be a finite number, got inf"),
]

# Options that only apply with another integrator or acceleration, for the NaN rows above.
CONTEXT = {"--chebyshev-rho": ["--acceleration", "chebyshev"],
           "--chebyshev-gamma": ["--acceleration", "chebyshev"],
           "--newton-tolerance": ["--integrator", "backward-euler"],
           "--penalty-weight": ["--pins", "penalty"]}
# (--duration and --progress need no context.)


def refusals(simulate, source, work, table):
    if table:
        print("| input | exit | message | on disk before and after |")
        print("|---|---|---|---|")
    for args, expected in REFUSALS:
        if args[1:2] and args[1] in CONTEXT and args[2] == "nan":
            args = args + CONTEXT[args[1]]
        prepare(source, work)
        before = snapshot(work)
        result = run(simulate, args, work)
        after = snapshot(work)
        command = "massspring-simulate " + " ".join(args)
        if table:
            same = "unchanged" if before == after else "CHANGED"
            print(f"| `{' '.join(args)}` | {result.returncode} | `{result.stderr.strip()}` | {same} |")
            continue
        check(result.returncode == 1, f"{command}: exit {result.returncode}, expected 1\n"
                                      f"{result.stdout}{result.stderr}")
        check(result.stderr == P + expected + "\n",
              f"{command}:\n  got      {result.stderr!r}\n  expected {P + expected!r}")
        check(result.stdout == "", f"{command}: printed {result.stdout!r} (a run started?)")
        check(before == after, f"{command}: the folder changed: "
                               f"{set(before.items()) ^ set(after.items())}")
    if not table:
        print(f"OK: {len(REFUSALS)} refusals, each exit 1 with its message, nothing written")


def help_text(simulate, source, work):
    result = run(simulate, ["--help"], work)
    help_text_out = result.stdout
    check(result.returncode == 0, f"--help: exit {result.returncode}")
    check(result.stderr == "", f"--help: stderr {result.stderr!r}")
    flags = {"--help", "--overwrite", "--quiet", "--version"}
    options = 0
    for line in result.stdout.splitlines():
        words = line.split()
        if not words or not words[0].startswith("--") and not words[0].startswith("-h,"):
            continue
        name = words[0].split("=")[0].split(":")[0].split(",")[-1]
        if name in flags:
            continue
        options += 1
        check("=" in words[0] or (len(words) > 1 and "=" in words[1]),
              f"--help shows no default for {name}: {line!r}")
    check(options >= 30, f"--help lists {options} options with values, expected every one")
    for name in ("--acceleration", "--chebyshev-rho", "--chebyshev-gamma", "--chebyshev-delay",
                 "--anderson-window", "--threads", "--ordering", "--newton-iterations",
                 "--newton-tolerance", "--line-search", "--save-state", "--save-every",
                 "--overwrite", "--self-collision"):
        check(name in result.stdout, f"--help does not list {name}")
    # --version: the project's version (CMake's project(VERSION), read from version.hpp), exit 0
    with open(os.path.join(source, "include", "massspring", "version.hpp")) as handle:
        parts = dict(re.findall(r"^#define MASSSPRING_VERSION_(MAJOR|MINOR|PATCH) (\d+)$",
                                handle.read(), re.M))
    expected = f"massspring-simulate {parts['MAJOR']}.{parts['MINOR']}.{parts['PATCH']}\n"
    for args in (["--version"], ["--generate", "chain", "--version"]):
        result = run(simulate, args, work)
        check(result.returncode == 0 and result.stdout == expected and result.stderr == "",
              f"{args}: exit {result.returncode}, {result.stdout!r} {result.stderr!r}, expected "
              f"{expected!r}")
    check("--version" in help_text_out, "--help does not list --version")
    print(f"OK: --help exits 0, {options} options each with a default; --version prints "
          f"{expected.strip()!r}")


def rows(path):
    with open(path) as handle:
        return handle.read().splitlines()


def overwrite(simulate, source, work):
    prepare(source, work)
    result = run(simulate, ["chain.json", "--frames", "4", "--csv", "existing.csv",
                            "--overwrite"], work)
    check(result.returncode == 0, f"--overwrite csv: exit {result.returncode} {result.stderr}")
    lines = rows(os.path.join(work, "existing.csv"))
    check(lines[0] == "frame,point,x,y,z,vx,vy,vz" and len(lines) == 1 + 5 * 10,
          f"existing.csv after --overwrite: {len(lines)} lines")
    out = os.path.join(work, "frames")
    check(run(simulate, ["chain.json", "--frames", "20", "--out", "frames"], work).returncode == 0,
          "20 frames")
    check(len(os.listdir(out)) == 21, "21 frames written")
    result = run(simulate, ["chain.json", "--frames", "3", "--out", "frames", "--overwrite"], work)
    check(result.returncode == 0, f"--overwrite --out: exit {result.returncode} {result.stderr}")
    names = sorted(os.listdir(out))
    check(names == [f"frame_{f:05d}.obj" for f in range(4)],
          f"--out after 20 then 3 frames with --overwrite: {names[:3]}... ({len(names)} files)")
    # A --save-state file can be replaced with --overwrite; without it, refused.
    check(run(simulate, ["chain.json", "--frames", "2", "--save-state", "s.json"], work)
          .returncode == 0, "save")
    check(run(simulate, ["chain.json", "--frames", "2", "--save-state", "s.json"], work)
          .returncode == 1, "a second --save-state to the same file without --overwrite")
    check(run(simulate, ["chain.json", "--frames", "2", "--save-state", "s.json", "--overwrite"],
              work).returncode == 0, "--save-state --overwrite")
    print("OK: --overwrite replaces the CSV, the state and the frames (4 files, not 21)")


def start_long_run(simulate, work, extra):
    process = subprocess.Popen(
        [simulate, "--generate", "cloth:20x15", "--frames", "100000000"] + extra,
        cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    header = process.stdout.readline()  # flushed before the first step, through a pipe
    check(process.poll() is None, f"the run ended before its header was read: {header!r}")
    check(header.startswith("--generate cloth:20x15: 300 points"), f"header {header!r}")
    return process


def rename(simulate, source, work):
    prepare(source, work)
    csv = os.path.join(work, "traj.csv")
    process = start_long_run(simulate, work, ["--csv", "traj.csv"])
    os.makedirs(csv)  # the final rename will fail: its target is now a folder
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and os.path.getsize(csv + ".tmp") < 200000:
        time.sleep(0.02)
    process.send_signal(signal.SIGINT)
    stdout, stderr = process.communicate(timeout=300)
    print(stdout, stderr, sep="")
    check(process.returncode == 130, f"exit {process.returncode}, expected 130")
    expected = (f"{P}traj.csv: cannot rename traj.csv.tmp to it (Is a directory); the trajectory "
                f"is kept, whole, in traj.csv.tmp\n")
    check(stderr.startswith(expected), f"message {stderr!r}, expected it to start {expected!r}")
    last = int(stderr.split("interrupted at frame ")[1].split(";")[0])
    lines = rows(csv + ".tmp")
    check(lines[0] == "frame,point,x,y,z,vx,vy,vz", "header of the kept .tmp")
    check(len(lines) == 1 + 300 * (last + 1), f"{len(lines)} lines in the .tmp for frames 0..{last}")
    check(lines[-1].startswith(f"{last},299,"), f"last row {lines[-1]!r}")
    print(f"OK: rename failed, traj.csv.tmp kept with frames 0..{last}")


def killed(simulate, source, work):
    prepare(source, work)
    tmp = os.path.join(work, "k.csv.tmp")
    process = start_long_run(simulate, work, ["--csv", "k.csv"])
    deadline = time.monotonic() + 300
    while (not os.path.exists(tmp) or os.path.getsize(tmp) < 100000) and \
            time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.02)
    check(process.poll() is None, "the run ended before it was killed")
    process.kill()
    process.communicate(timeout=60)
    check(os.path.exists(tmp) and not os.path.exists(os.path.join(work, "k.csv")),
          "SIGKILL: k.csv.tmp left, no k.csv")
    before = snapshot(work)
    result = run(simulate, ["chain.json", "--frames", "2", "--csv", "k.csv"], work)
    check(result.returncode == 1 and "k.csv.tmp exists, left by an earlier run" in result.stderr,
          f"the next run: exit {result.returncode} {result.stderr!r}")
    check(snapshot(work) == before, "the refused run changed the folder")
    result = run(simulate, ["chain.json", "--frames", "2", "--csv", "k.csv", "--overwrite"], work)
    check(result.returncode == 0, f"--overwrite: {result.returncode} {result.stderr}")
    check(not os.path.exists(tmp) and len(rows(os.path.join(work, "k.csv"))) == 1 + 3 * 10,
          "--overwrite: k.csv whole, no .tmp")
    print("OK: a killed run's .tmp is named and kept; --overwrite replaces it")


def options(simulate, source, work):
    prepare(source, work)
    base = ["--generate", "cloth:12x10", "--frames", "15", "--iterations", "5"]

    def csv_of(name, extra, header=None):
        args = base if "--integrator" not in extra else base[:4]  # no --iterations
        result = run(simulate, args + extra + ["--csv", name], work)
        check(result.returncode == 0, f"{extra}: exit {result.returncode} {result.stderr}")
        if header:
            check(header in result.stdout.splitlines()[0], f"{extra}: header {result.stdout!r}")
        return rows(os.path.join(work, name))

    plain = csv_of("plain.csv", ["--acceleration", "none"],
                   "fast-mass-spring (exact pins, 5 iterations)")
    chebyshev = csv_of("cheb.csv", ["--acceleration", "chebyshev", "--chebyshev-delay", "1"],
                       "5 iterations, chebyshev)")
    anderson = csv_of("anderson.csv", ["--acceleration", "anderson", "--anderson-window", "3"],
                      "5 iterations, anderson)")
    check(plain != chebyshev and plain != anderson and chebyshev != anderson,
          "the accelerations give the plain trajectory: the option does not reach the solver")
    check(csv_of("rho.csv", ["--acceleration", "chebyshev", "--chebyshev-delay", "1",
                             "--chebyshev-rho", "0.3"]) != chebyshev, "--chebyshev-rho ignored")
    for order in ("solver", "nested-dissection"):
        csv_of(f"order_{order}.csv", ["--ordering", order])
    threads = run(simulate, base + ["--acceleration", "none", "--threads", "2", "--csv",
                                    "threads.csv"], work)
    if threads.returncode == 0:
        check(rows(os.path.join(work, "threads.csv")) == plain, "--threads 2 changed the result")
    else:  # built without OpenMP: the solver's refusal, with exit 1
        check(threads.returncode == 1 and "threads" in threads.stderr, threads.stderr)
    newton = ["--integrator", "backward-euler"]
    loose = csv_of("loose.csv", newton + ["--newton-tolerance", "1e-2", "--newton-iterations",
                                          "2", "--line-search", "off"], "backward-euler")
    tight = csv_of("tight.csv", newton, "backward-euler")
    check(loose != tight, "backward Euler's tolerance and iterations do not reach the solver")
    print("OK: accelerations, rho, orderings, threads and Newton options reach the solver")


def csv_frames(path):
    """The frame numbers in a trajectory CSV, in order, each once."""
    frames = []
    for row in rows(path)[1:]:
        f = int(row.split(",")[0])
        if not frames or frames[-1] != f:
            frames.append(f)
    return frames


def length(simulate, source, work):
    prepare(source, work)

    def ok(args):
        result = run(simulate, args, work)
        check(result.returncode == 0, f"{args}: exit {result.returncode} {result.stderr}")
        return result

    # --duration D: the whole number of steps nearest D / dt, at least one, so that the run ends
    # within dt / 2 of D: 1 s at dt 0.01 is 100 steps; 0.104 s is 10 and 0.106 s is 11; 0.3 s at
    # 0.1 is 3 (0.3 / 0.1 = 2.9999999999999996); 1.5 s at 0.0333333 (the README's drape) is 45,
    # not 46 (1.5333 s); 0.001 s at 0.01 is one step
    for duration, dt, steps in (("1", "0.01", 100), ("0.104", "0.01", 10), ("0.106", "0.01", 11),
                                ("0.3", "0.1", 3), ("1.5", "0.0333333", 45),
                                ("0.001", "0.01", 1)):
        result = ok(["chain.json", "--duration", duration, "--dt", dt, "--csv", "d.csv",
                     "--overwrite"])
        check(csv_frames(os.path.join(work, "d.csv")) == list(range(steps + 1)),
              f"--duration {duration} --dt {dt}: frames {csv_frames(os.path.join(work, 'd.csv'))}")
        check(f"{steps} steps" in result.stdout.splitlines()[0], f"header {result.stdout!r}")
        check(steps == 1 or abs(steps * float(dt) - float(duration)) <= float(dt) / 2,
              f"--duration {duration} --dt {dt}: {steps} steps end at {steps * float(dt)} s")
    # --frames counts written frames: 5 after the first, every 3rd step: 15 steps
    ok(["chain.json", "--frames", "5", "--every", "3", "--out", "f"])
    names = sorted(os.listdir(os.path.join(work, "f")))
    check(names == [f"frame_{k:05d}.obj" for k in range(0, 16, 3)], f"--frames 5 --every 3: {names}")
    # --steps: the steps themselves, frames every 4th and the last
    ok(["chain.json", "--steps", "10", "--every", "4", "--csv", "s.csv"])
    check(csv_frames(os.path.join(work, "s.csv")) == [0, 4, 8, 10], "--steps 10 --every 4")
    # the default: 300 steps
    ok(["chain.json", "--every", "100", "--csv", "default.csv"])
    check(csv_frames(os.path.join(work, "default.csv")) == [0, 100, 200, 300], "default length")
    # a JSON scene's own "gravity" and "dt" (own_gravity.json: chain.json's cloth with
    # gravity (0, -1, 0) and dt 0.01) give the run of chain.json with them as options, bit for bit
    own = ok(["own_gravity.json", "--steps", "30", "--csv", "own.csv"])
    check("dt 0.01 s, 30 steps (0.3 s)" in own.stdout, f"header {own.stdout!r}")
    check("1 force terms" in own.stdout, f"one gravity term, not two: {own.stdout!r}")
    with open(os.path.join(work, "plain.json"), "w") as handle:
        handle.write('{"obj": "chain.obj", "b": [1], "k": 10, "m": 1}\n')
    ok(["plain.json", "--steps", "30", "--dt", "0.01", "--gravity", "0,-1,0", "--csv",
        "given.csv"])
    check(rows(os.path.join(work, "own.csv")) == rows(os.path.join(work, "given.csv")),
          "a scene's own gravity and dt differ from the same given as options")
    # --dt replaces the scene's own
    other = ok(["own_gravity.json", "--steps", "3", "--dt", "0.02"])
    check("dt 0.02 s" in other.stdout, f"--dt with a scene's dt: {other.stdout!r}")
    print("OK: --duration, --frames, --steps and the default set the length; a scene's own "
          "gravity and dt are used")


PROGRESS = re.compile(r"^step (\d+) of (\d+) \((\d+)%\): ([0-9.e+-]+) s of ([0-9.e+-]+) s "
                      r"simulated; ([0-9.]+) s elapsed, about ([0-9.]+) s left$")


def progress(simulate, source, work):
    prepare(source, work)
    args = ["--generate", "cloth:20x15", "--steps", "60", "--iterations", "20"]
    result = run(simulate, args + ["--progress", "0.000001"], work)
    check(result.returncode == 0, f"exit {result.returncode} {result.stderr}")
    lines = [line for line in result.stdout.splitlines() if line.startswith("step ")]
    check(len(lines) >= 1, f"no progress line in {result.stdout!r}")
    done = []
    for line in lines:
        match = PROGRESS.match(line)
        check(match is not None, f"progress line {line!r}")
        step, total = int(match.group(1)), int(match.group(2))
        check(total == 60 and 1 <= step <= 60, line)
        check(abs(float(match.group(4)) - step / 30) < 1e-3 and float(match.group(5)) == 2, line)
        done.append(step)
    check(done == sorted(set(done)), f"steps not increasing: {done}")
    for extra in (["--quiet", "--progress", "0.000001"], [], ["--progress", "0"]):
        result = run(simulate, args + extra, work)
        check(result.returncode == 0 and "step 1 of" not in result.stdout and
              not any(line.startswith("step ") for line in result.stdout.splitlines()),
              f"{extra}: progress lines in {result.stdout!r}")
    print(f"OK: {len(lines)} progress lines with --progress; none with --quiet, 0 or a short run")


def hint(simulate, source, work):
    prepare(source, work)
    prefix = P + "hint: "
    # symplectic Euler at dt 1 s on a chain: diverges; the hint's step runs it stably
    result = run(simulate, ["--generate", "chain:10", "--integrator", "symplectic-euler", "--dt",
                            "1", "--steps", "1000"], work)
    check(result.returncode == 2, f"exit {result.returncode}")
    lines = [line for line in result.stderr.splitlines() if line.startswith(prefix)]
    check(len(lines) == 1, f"stderr {result.stderr!r}")
    match = re.match(re.escape(prefix) + r"--dt 1 is above the step symplectic-euler is stable at "
                     r"on this scene: stable_time_step\(\) gives ([0-9.e+-]+) s at the first "
                     r"state; try --dt \1, or an implicit integrator \(--integrator "
                     r"backward-euler or fast-mass-spring\) is stable at any --dt$", lines[0])
    check(match is not None, f"hint {lines[0]!r}")
    step = match.group(1)
    again = run(simulate, ["--generate", "chain:10", "--integrator", "symplectic-euler", "--dt",
                           step, "--steps", "2000"], work)
    check(again.returncode == 0, f"--dt {step}: exit {again.returncode} {again.stderr}")
    # forward Euler without drag: no stable step; the hint names symplectic Euler's
    result = run(simulate, ["--generate", "chain:10", "--integrator", "forward-euler", "--dt",
                            "0.1", "--steps", "100000"], work)
    check(result.returncode == 2, f"forward Euler: exit {result.returncode}")
    match = re.search(re.escape(prefix) + r"forward-euler is unstable at every --dt on this scene "
                      r"\(springs without linear drag\); symplectic-euler is stable at --dt "
                      r"([0-9.e+-]+) \(stable_time_step\(\) at the first state\), or an implicit "
                      r"integrator", result.stderr)
    check(match is not None, f"forward Euler's hint: {result.stderr!r}")
    check(match.group(1) == step, f"symplectic step {match.group(1)} != {step}")
    # an implicit integrator gets no hint
    result = run(simulate, ["--generate", "chain:10", "--integrator", "backward-euler", "--dt",
                            "1", "--steps", "5"], work)
    check(prefix not in result.stderr, f"backward Euler: {result.stderr!r}")
    # linearised BackwardEuler on the flag at 1/30 s: its second step's linear solve goes uphill
    # on the incremental potential; refused, and the second line says that it can be why
    flag = os.path.join(source, "examples", "scenes", "flag.json")
    result = run(simulate, [flag, "--integrator", "linearized-backward-euler", "--steps", "10",
                            "--out", os.path.join(work, "flag_frames")], work)
    check(result.returncode == 2, f"linearised flag: exit {result.returncode} {result.stderr!r}")
    check(P + "step 2: the total energy passed the divergence limit" in result.stderr and
          P + "linearized-backward-euler also refuses a step whose one linear solve raises the "
          "incremental potential it linearises" in result.stderr,
          f"linearised flag: {result.stderr!r}")
    print(f"OK: the hint's step {step} s runs symplectic Euler 2000 steps without diverging")


def folders(simulate, source, work):
    """Every output creates the missing folders of its path: one rule for all of them."""
    prepare(source, work)
    outputs = {"--out": "new/out/frames", "--csv": "new/csv/t.csv", "--html": "new/html/p.html",
               "--pc2": "new/pc2/c.pc2", "--vtk": "new/vtk/series",
               "--save-state": "new/state/s.json"}
    written = {"--out": "new/out/frames/frame_00003.obj", "--pc2": "new/pc2/c.obj",
               "--vtk": "new/vtk/series/run.pvd"}
    for option, path in outputs.items():
        result = run(simulate, ["chain.json", "--steps", "3", option, path], work)
        check(result.returncode == 0, f"{option} {path}: exit {result.returncode} {result.stderr}")
        for f in (path, written.get(option, path)):
            check(os.path.exists(os.path.join(work, f)), f"{option} {path}: {f} not written")
    # all at once, two levels deep
    args = ["chain.json", "--steps", "3"]
    for option, path in outputs.items():
        args += [option, "all/x/" + path]
    result = run(simulate, args, work)
    check(result.returncode == 0, f"{args}: exit {result.returncode} {result.stderr}")
    for option, path in outputs.items():
        check(os.path.exists(os.path.join(work, "all/x/" + written.get(option, path))),
              f"all at once: {option} not written")
    help_out = run(simulate, ["--help"], work).stdout
    check("missing folders" in " ".join(help_out.split()), "--help does not state the rule")
    print(f"OK: {len(outputs)} outputs each create the missing folders of their path")


def readme(simulate, source, work):
    """The README's massspring-simulate commands, as printed, twice, in a copy of the scenes."""
    shutil.rmtree(work, ignore_errors=True)
    # the binary where the README's commands name it (the path scripts/demo.sh builds:
    # tests/scripts/readme_commands.py)
    with open(os.path.join(source, "README.md")) as handle:
        named = re.search(r"^(\S+/massspring-simulate) ", handle.read(), re.M)
    check(named is not None, "no README line starts with a path to massspring-simulate")
    os.makedirs(os.path.dirname(os.path.join(work, named.group(1))))
    os.symlink(simulate, os.path.join(work, named.group(1)))
    for folder in ("scenes", "scenes_xml"):
        shutil.copytree(os.path.join(source, "examples", folder),
                        os.path.join(work, "examples", folder))
    blocks, block, inside = [], [], False
    with open(os.path.join(source, "README.md")) as handle:
        for line in handle.read().splitlines():
            if inside and line == "```":
                inside = False
                if any("massspring-simulate" in b for b in block):
                    blocks.append("\n".join(block))
            elif inside:
                block.append(line)
            elif line == "```sh":
                inside, block = True, []
    check(len(blocks) >= 3, f"{len(blocks)} README blocks run massspring-simulate")
    before = snapshot(work)
    for attempt in (1, 2):
        for text in blocks:
            result = subprocess.run(["bash", "-euo", "pipefail", "-c", text], cwd=work,
                                    capture_output=True, text=True, timeout=900)
            check(result.returncode == 0,
                  f"run {attempt} of the README's\n{text}\nexit {result.returncode}: "
                  f"{result.stderr}")
    after = snapshot(work)
    written = sorted(set(after) - set(before))
    outside = [f for f in written if not f.startswith("out/")]
    check(not outside, f"the README's commands wrote outside out/: {outside}")
    changed = [f for f in before if before[f] != after.get(f)]
    check(not changed, f"the README's commands changed {changed}")
    print(f"OK: {len(blocks)} README blocks ran twice; {len(written)} files, all under out/")


def write_contact_scene(work):
    """contact.json: a 5 x 5 cloth lying on a plane that rises, with a sphere, a capsule, a box
    and a mesh (bump.obj), every one moving, so that contact happens from the first step."""
    with open(os.path.join(work, "contact_cloth.obj"), "w") as handle:
        for r in range(5):
            for c in range(5):
                handle.write(f"v {c / 4} 0.5 {r / 4}\n")
        for r in range(4):
            for c in range(4):
                a = r * 5 + c + 1
                handle.write(f"f {a} {a + 1} {a + 6} {a + 5}\n")
    with open(os.path.join(work, "bump.obj"), "w") as handle:
        handle.write("v 0.1 0.45 0.1\nv 0.7 0.45 0.3\nv 0.1 0.55 0.9\nv 0.9 0.5 0.7\n"
                     "f 1 2 3\nf 2 4 3\n")
    with open(os.path.join(work, "contact.json"), "w") as handle:
        handle.write("""{"obj": "contact_cloth.obj", "b": [], "k": 100, "m": 0.05,
  "colliders": [
    {"type": "plane", "point": [0, 0.5, 0], "normal": [0.01, 1, 0.02], "friction": 0.3,
     "velocity": [0, 0.2, 0]},
    {"type": "sphere", "center": [0.5, 0.45, 0.5], "radius": 0.1,
     "friction": {"static": 0.5, "kinetic": 0.3}, "velocity": [0, 1, 0],
     "angular_velocity": [0, 3, 0]},
    {"type": "capsule", "a": [0, 0.55, 0.2], "b": [1, 0.55, 0.3], "radius": 0.03,
     "friction": 0.2, "angular_velocity": [5, 0, 0]},
    {"type": "box", "center": [0.2, 0.5, 0.8], "half_extents": [0.1, 0.05, 0.1],
     "rotation": [0.9, 0.1, 0.3, 0.2], "restitution": 0.5, "thickness": 0.01,
     "velocity": [0.1, 0, 0], "angular_velocity": [0, 2, 0]},
    {"type": "mesh", "obj": "bump.obj", "velocity": [0, 0.1, 0],
     "angular_velocity": [0, 0, 0.5], "thickness": 0.005}]}
""")


def resume(simulate, source, work):
    prepare(source, work)
    write_contact_scene(work)
    # (scene, options): the resumed run gets the options again, except --dt and --integrator,
    # which the state file records (with the frame number and Chebyshev's rho).
    cases = [
        (["--generate", "cloth:8x6"], []),
        (["--generate", "cloth:8x6"], ["--acceleration", "chebyshev", "--iterations", "10"]),
        (["--generate", "cloth:8x6"], ["--acceleration", "anderson", "--iterations", "10"]),
        (["--generate", "chain:12"], ["--integrator", "backward-euler"]),
        (["--generate", "chain:12"], ["--shrink", "0.5", "--precision", "float"]),
        (["chain.json"], ["--integrator", "symplectic-euler", "--dt", "0.002"]),
        # colliders of every kind, moving, with every integrator
        (["contact.json"], []),
        (["contact.json"], ["--acceleration", "chebyshev", "--iterations", "10"]),
        # contact inside the iteration: the state holds the contact term's dual variables
        (["contact.json"], ["--contact-weight", "1", "--acceleration", "anderson", "--iterations", "10"]),
        (["contact.json"], ["--integrator", "symplectic-euler", "--dt", "0.002"]),
        (["contact.json"], ["--integrator", "forward-euler", "--dt", "0.0005"]),
        (["contact.json"], ["--integrator", "backward-euler"]),
        # (linearised BackwardEuler at 0.02 s: at 1/30 s its one linear solve a step cannot hold
        # this coarse cloth under four spinning colliders, and the energy bound refuses step 7)
        (["contact.json"], ["--integrator", "linearized-backward-euler", "--dt", "0.02"]),
        (["contact.json"], ["--integrator", "backward-euler", "--contact-weight", "1"]),
        (["contact.json"], ["--integrator", "linearized-backward-euler", "--contact-weight", "1",
                            "--dt", "0.02"]),
        # self-collision: the state holds the surface and the thickness
        (["--generate", "cloth:8x6"], ["--self-collision", "0.01"]),
        # an XML scene's gravitational attraction, and a JSON scene's own gravity and dt
        (["orbit.xml"], []),
        (["own_gravity.json"], []),
    ]
    for k, (scene, options) in enumerate(cases):
        whole, first, second, state = (f"r{k}_20.csv", f"r{k}_a.csv", f"r{k}_b.csv",
                                       f"r{k}_state.json")
        again = [o for i, o in enumerate(options) if o not in ("--dt", "--integrator") and
                 (i == 0 or options[i - 1] not in ("--dt", "--integrator"))]
        args = scene + options
        for command in (args + ["--frames", "20", "--csv", whole],
                        args + ["--frames", "10", "--csv", first, "--save-state", state],
                        [state, "--frames", "10", "--csv", second] + again):
            result = run(simulate, command, work)
            check(result.returncode == 0, f"{command}: exit {result.returncode} {result.stderr}")
        if "--self-collision" in options:
            with open(os.path.join(work, state)) as handle:
                saved = json.load(handle)
            check(saved.get("self_collision") == {"thickness": 0.01, "friction": 0.2} and
                  len(saved.get("surface", [])) == 2 * 7 * 5,
                  f"{args}: the state does not hold the surface and self-collision")
        a, b, c = (rows(os.path.join(work, f)) for f in (whole, first, second))
        check(b[0] == c[0] == a[0], "CSV headers")
        # the saved frame 10 is in both halves, equal; together they are the 20 frames exactly
        tail = [r for r in c[1:] if not r.startswith("10,")]
        check([r for r in b[1:] if r.startswith("10,")] == [r for r in c[1:] if r.startswith("10,")],
              f"{args}: frame 10 differs between the first run's end and the resumed start")
        check(a == b + tail, f"{args}: 10 + 10 frames differ from 20 frames")
        check(all(r.split(",")[0] in {str(f) for f in range(10, 21)} for r in c[1:]),
              f"{args}: the resumed run numbers its frames 10..20")
    # A state whose contact dual variables do not fit the scene is refused before a file is
    # written, naming the key.
    for k in (i for i, (_, o) in enumerate(cases) if "--contact-weight" in o):
        with open(os.path.join(work, f"r{k}_state.json")) as handle:
            saved = json.load(handle)
        check(len(saved["run"]["contact_duals"]) == len(saved["positions"]) and
              any(any(x != 0 for x in row) for row in saved["run"]["contact_duals"]),
              f"{cases[k][1]}: the state does not hold the contact term's dual variables")
    k = next(i for i, (_, o) in enumerate(cases) if "--contact-weight" in o)
    with open(os.path.join(work, f"r{k}_state.json")) as handle:
        saved = json.load(handle)
    for duals, message in ((saved["run"]["contact_duals"][:-1],
                            f"has {len(saved['positions']) - 1} rows for "
                            f"{len(saved['positions'])} points"),
                           ([[0, 0]] * len(saved["positions"]), "row 0 is not three numbers")):
        saved["run"]["contact_duals"] = duals
        with open(os.path.join(work, "bad_duals.json"), "w") as handle:
            json.dump(saved, handle)
        before = snapshot(work)
        result = run(simulate, ["bad_duals.json", "--contact-weight", "1", "--csv", "bad.csv"],
                     work)
        check(result.returncode == 1 and 'bad_duals.json: key "run": "contact_duals" ' + message
              in result.stderr, f"bad contact_duals: {result.returncode} {result.stderr!r}")
        check(snapshot(work) == before, "bad contact_duals: the folder changed")
    # Without --shrink's rest lengths at frame 0 a state cannot resume a shrinking run.
    result = run(simulate, ["r0_state.json", "--shrink", "0.5"], work)
    check(result.returncode == 1 and "was not saved by a run with the same --shrink" in
          result.stderr, f"--shrink on a state without it: {result.stderr!r}")
    print(f"OK: {len(cases)} runs resumed bit for bit (10 + 10 frames == 20 frames)")


WORK = re.compile(r"^the contact response added energy in (\d+) steps, at most ([0-9.e+-]+) J "
                  r"\(step (\d+); the scene's energy scale is ([0-9.e+-]+) J\)")


def contact_work_line(simulate, source, work_dir):
    scenes = os.path.join(source, "examples", "scenes")
    for name, expected in (("drape", False), ("clothesline", True)):
        for extra in ([], ["--quiet"]):
            args = [os.path.join(scenes, name + ".json"), "--dt", "0.0333333333333", "--duration",
                    "3"] + extra
            result = run(simulate, args, work_dir)
            check(result.returncode == 0,
                  f"{name} {extra}: exit {result.returncode} {result.stderr}")
            lines = [m for m in map(WORK.match, result.stdout.splitlines()) if m]
            if extra:
                check(not lines, f"{name} --quiet: {result.stdout!r}")
                continue
            check(bool(lines) == expected, f"{name}: {result.stdout!r}")
            if lines:
                steps, most, at, scale = lines[0].groups()
                check(1 <= int(steps) <= 90 and 1 <= int(at) <= 90, lines[0].group(0))
                check(float(most) > 1e-3 * float(scale) > 0, lines[0].group(0))
    print("OK: no contact-work line for the drape, one for the clothesline; none with --quiet")


def main():
    table = "--table" in sys.argv
    argv = [a for a in sys.argv if a != "--table"]
    if len(argv) != 5:
        fail(__doc__)
    simulate, source, work, case = argv[1:]
    simulate = os.path.abspath(simulate)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    cases = {"refusals": lambda: refusals(simulate, source, work, table),
             "help": lambda: help_text(simulate, source, work),
             "overwrite": lambda: overwrite(simulate, source, work),
             "rename": lambda: rename(simulate, source, work),
             "killed": lambda: killed(simulate, source, work),
             "options": lambda: options(simulate, source, work),
             "length": lambda: length(simulate, source, work),
             "progress": lambda: progress(simulate, source, work),
             "hint": lambda: hint(simulate, source, work),
             "readme": lambda: readme(simulate, source, work),
             "folders": lambda: folders(simulate, source, work),
             "resume": lambda: resume(simulate, source, work),
             "work": lambda: contact_work_line(simulate, source, work)}
    if case not in cases:
        fail(f"unknown case {case}")
    cases[case]()
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
