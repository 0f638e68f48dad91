"""A scene stepped from Python equals massspring-simulate's trajectory bit for bit.

The C++ side is the real binary (MASSSPRING_SIMULATE, set by ctest when the examples are built),
writing its CSV trajectory with 17 significant digits (exact for doubles); the Python side loads
the same file, adds the same force terms, configures the same integrator and steps the same
number of frames. Every position and velocity of every frame must be the same double. Most runs
turn the CLI's energy guard off (--guard-growth 0) and step plainly; the runs marked `guard` keep
the CLI's default (growth 100) and step through massspring.DivergenceGuard. Scenes are files, or
generated (--generate cloth:20x15 against make_cloth)."""

import csv
import os
import subprocess

import numpy as np
import pytest

import massspring as ms
from conftest import scene

SIMULATE = os.environ.get("MASSSPRING_SIMULATE", "")

# ctest sets MASSSPRING_SIMULATE when the examples are configured (then the binary must be there:
# a missing one fails the test), and leaves it empty with MASSSPRING_BUILD_EXAMPLES=OFF.
pytestmark = pytest.mark.skipif(
    not SIMULATE,
    reason="massspring-simulate is not built (MASSSPRING_BUILD_EXAMPLES=OFF); set "
           "MASSSPRING_SIMULATE to the binary to compare with it")

# FOSSSim's integrator names (an XML scene's own) and the CLI's.
INTEGRATORS = {
    "fast-mass-spring": ms.FastMassSpring,
    "forward-euler": ms.ForwardEuler,
    "explicit-euler": ms.ForwardEuler,
    "symplectic-euler": ms.SymplecticEuler,
    "backward-euler": ms.BackwardEuler,
    "implicit-euler": ms.BackwardEuler,
    "linearized-backward-euler": ms.BackwardEuler,
    "linearized-implicit-euler": ms.BackwardEuler,
}


def cli_trajectory(tmp_path, path, frames, args, guard=False):
    assert os.path.exists(SIMULATE), f"MASSSPRING_SIMULATE={SIMULATE}: no such file (build it)"
    out = tmp_path / "trajectory.csv"
    source = ["--generate", path[len("generate:"):]] if path.startswith("generate:") else [path]
    run = subprocess.run([SIMULATE] + source + ["--frames", str(frames), "--csv", str(out),
                                                "--quiet"]
                         + ([] if guard else ["--guard-growth", "0"]) + args,
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    with open(out, newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == ["frame", "point", "x", "y", "z", "vx", "vy", "vz"]
    data = np.array([[float(v) for v in row[2:]] for row in rows[1:]])  # float(): exact
    return data.reshape(frames + 1, -1, 6)


def generated(spec):
    """massspring-simulate's --generate KIND:SIZE, from Python."""
    kind, size = spec.split(":")
    if kind == "chain":
        options = ms.ChainOptions()
        options.points = int(size)
        return ms.make_system(ms.make_chain(options))
    options = ms.ClothOptions() if kind == "cloth" else ms.NetOptions()
    options.columns, options.rows = (int(v) for v in size.split("x"))
    return ms.make_system(ms.make_cloth(options) if kind == "cloth" else ms.make_net(options))


class Generated:
    """What load_scene_file gives, for a generated scene."""

    def __init__(self, spec):
        self.system, self.fosssim = generated(spec), None


def python_trajectory(path, frames, integrator=None, dt=None, iterations=None,
                      acceleration=None, guard=False):
    if path.startswith("generate:"):
        loaded = Generated(path[len("generate:"):])
    else:
        loaded = ms.load_scene_file(path)
    s = loaded.system
    if loaded.fosssim is None:
        if "gravity" not in s.forces:  # a JSON scene's own "gravity", else the CLI's default
            s.add_force(ms.Gravity([0, -9.8, 0]))
        integrator = integrator or "fast-mass-spring"
        dt = dt or getattr(loaded, "dt", None) or 1.0 / 30  # --dt, the scene's "dt", 1/30
    else:  # an XML scene runs with its own integrator and dt unless told otherwise
        integrator = integrator or loaded.fosssim.integrator
        dt = dt or loaded.fosssim.dt
    solver = INTEGRATORS[integrator]()
    if isinstance(solver, ms.FastMassSpring):
        if iterations:
            solver.options.iterations = iterations
        if acceleration:
            solver.options.acceleration = acceleration
    if isinstance(solver, ms.BackwardEuler) and integrator.startswith("linearized"):
        solver.options.mode = ms.BackwardEulerMode.Linearized
    solver.precompute(s, dt)
    checked = ms.DivergenceGuard(s, 100.0) if guard else None
    states = [np.hstack([s.positions, s.velocities])]
    for _ in range(frames):
        report = checked.step(solver, s) if guard else solver.step(s)
        assert report.ok()
        states.append(np.hstack([s.positions, s.velocities]))
    return np.array(states)


CASES = [
    # scene, frames, CLI arguments, python_trajectory keywords
    ("flag.json", 10, [], {}),
    ("flag.json", 10, ["--iterations", "10", "--acceleration", "chebyshev"],
     {"iterations": 10, "acceleration": ms.Acceleration.Chebyshev}),
    # plane and sphere colliders: at dt 1/200 s the cloth lands on the ball (about frame 50)
    ("drape.json", 100, ["--iterations", "10", "--dt", "0.005"], {"iterations": 10, "dt": 0.005}),
    # its own "dt" (0.005) and "gravity"
    ("drape.json", 40, ["--iterations", "10"], {"iterations": 10}),
    ("table.json", 20, ["--iterations", "10", "--acceleration", "anderson"],
     {"iterations": 10, "acceleration": ms.Acceleration.Anderson}),
    ("chain.json", 20, ["--integrator", "backward-euler", "--dt", "0.01"],
     {"integrator": "backward-euler", "dt": 0.01}),
    ("net.json", 20, ["--integrator", "linearized-backward-euler", "--dt", "0.01"],
     {"integrator": "linearized-backward-euler", "dt": 0.01}),
    ("chain.json", 50, ["--integrator", "symplectic-euler", "--dt", "0.001"],
     {"integrator": "symplectic-euler", "dt": 0.001}),
    ("tilted.json", 40, ["--integrator", "symplectic-euler", "--dt", "0.0005"],
     {"integrator": "symplectic-euler", "dt": 0.0005}),
    ("orbit.xml", 200, [], {}),  # the scene's own integrator and dt
    ("cantilever.xml", 100, [], {}),
    ("orbit.xml", 100, ["--integrator", "forward-euler"], {"integrator": "forward-euler"}),
    # the CLI's default energy guard, through massspring.DivergenceGuard
    ("flag.json", 10, [], {"guard": True}),
    ("orbit.xml", 100, ["--integrator", "symplectic-euler"],
     {"integrator": "symplectic-euler", "guard": True}),
    ("chain.json", 20, ["--integrator", "backward-euler", "--dt", "0.01"],
     {"integrator": "backward-euler", "dt": 0.01, "guard": True}),
    # generated scenes: make_cloth, make_chain, make_net
    ("generate:cloth:20x15", 20, ["--iterations", "10"], {"iterations": 10}),
    ("generate:chain:12", 30, ["--integrator", "symplectic-euler", "--dt", "0.001"],
     {"integrator": "symplectic-euler", "dt": 0.001}),
    ("generate:net:6x5", 20, [], {}),
]


def case_id(case):
    name, _, args, keywords = case
    return "-".join([name] + args[1::2] + (["guard"] if keywords.get("guard") else []))


@pytest.mark.parametrize("name, frames, args, keywords", CASES, ids=[case_id(c) for c in CASES])
def test_python_equals_the_cli_bit_for_bit(tmp_path, name, frames, args, keywords):
    path = name if name.startswith("generate:") else scene(name)
    want = cli_trajectory(tmp_path, path, frames, args, keywords.get("guard", False))
    got = python_trajectory(path, frames, **keywords)
    assert got.shape == want.shape
    moved = np.abs(want[-1, :, :3] - want[0, :, :3]).max()
    assert moved > 0  # the scene moved: the comparison is not of two copies of the start
    differ = np.argwhere(got != want)
    assert differ.size == 0, (
        f"{len(differ)} values differ; first at frame {differ[0][0]}, point {differ[0][1]}, "
        f"column {differ[0][2]}: Python {got[tuple(differ[0])]!r}, C++ {want[tuple(differ[0])]!r}")
