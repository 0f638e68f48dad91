"""massspring.sweep (docs/sweeps.md) on a local Dask cluster of 2 worker processes:

- a sweep of 8 runs (4 entries of `runs` x a grid of 2 frame counts) gives each run's final
  positions and velocities bit for bit equal to massspring-simulate's (the command line the file
  records for it, --csv written with 17 digits) and to a plain Python loop;
- a worker killed during the sweep (this test kills one while it runs a task) still gives all 8,
  the lost runs done by the other worker;
- a rerun on the finished file runs nothing (`python3 -m massspring.sweep`, the file unchanged);
- a spec with a bad value is refused before any run, naming the entry (no file written);
- a run that diverges and one that fails are recorded with their messages, the others done;
- Dask's own output stays off stderr (its log lines, a worker's traceback) when a worker of the
  sweep's local cluster is killed and on Ctrl-C, unless `verbose`; the logging set-up and the
  environment are as they were afterwards.

Skipped, with the reason, when Dask or h5py is absent (Debian: python3-dask python3-distributed
python3-h5py; scripts/setup.sh installs them)."""

import csv
import json
import logging
import os
import signal
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("dask", reason="Dask is not installed (Debian: python3-dask)")
distributed = pytest.importorskip("distributed",
                                  reason="dask.distributed is not installed (Debian: "
                                         "python3-distributed)")
h5py = pytest.importorskip("h5py", reason="h5py is not installed (Debian: python3-h5py)")

import massspring as ms  # noqa: E402
from massspring.sweep import SpecError, sweep  # noqa: E402
from conftest import scene  # noqa: E402
from test_simulate_cli import python_trajectory  # noqa: E402

SIMULATE = os.environ.get("MASSSPRING_SIMULATE", "")

# 4 runs x 2 frame counts; every one also a massspring-simulate command line. Small scenes, few
# steps: each run takes a few milliseconds to a few tenths of a second.
RUNS = [
    {"generate": "cloth:12x10", "iterations": 10, "acceleration": "chebyshev"},
    {"scene": "chain.json", "integrator": "backward-euler", "dt": 0.01},
    {"scene": "net.json", "integrator": "linearized-backward-euler", "dt": 0.01},
    {"scene": "drape.json", "iterations": 10},
]
GRID = {"frames": [8, 16]}


def write_spec(folder, runs=RUNS, grid=GRID, base=None):
    spec = {"runs": [dict(r) for r in runs], "grid": grid}
    if base:
        spec["base"] = base
    for r in spec["runs"]:
        if "scene" in r:
            r["scene"] = scene(r["scene"])
    path = os.path.join(folder, "spec.json")
    with open(path, "w") as handle:
        json.dump(spec, handle)
    return path


@pytest.fixture(scope="module")
def cluster():
    """2 worker processes, one thread each (as `python3 -m massspring.sweep --workers 2`)."""
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as c:
        yield c


@pytest.fixture(scope="module")
def finished(cluster, tmp_path_factory):
    """The 8-run sweep, done once: (spec, results file, summary)."""
    folder = tmp_path_factory.mktemp("sweep")
    spec = write_spec(str(folder))
    out = str(folder / "results.h5")
    summary = sweep(spec, out, scheduler=cluster.scheduler_address, progress=False)
    return spec, out, summary


def runs_in(path):
    with h5py.File(path, "r") as f:
        return {k: {"attrs": dict(g.attrs),
                    "final_positions": g["final_positions"][()] if "final_positions" in g
                    else None,
                    "final_velocities": g["final_velocities"][()] if "final_velocities" in g
                    else None}
                for k, g in f["runs"].items()}


def loop(parameters):
    """The run through a plain Python loop (test_simulate_cli's, under the CLI's default energy
    guard, as the sweep's default guard_growth 100)."""
    path = (parameters["scene"] if "scene" in parameters
            else "generate:" + parameters["generate"])
    accelerations = {"chebyshev": ms.Acceleration.Chebyshev}
    states = python_trajectory(path, parameters["frames"],
                               integrator=parameters.get("integrator"),
                               dt=parameters.get("dt"),
                               iterations=parameters.get("iterations"),
                               acceleration=accelerations.get(parameters.get("acceleration")),
                               guard=True)
    return states[-1]


def test_eight_runs_equal_the_cli_and_a_python_loop(finished, tmp_path):
    _, out, summary = finished
    assert summary == {"runs": 8, "skipped": 0, "ran": 8, "ok": 8, "not_ok": 0}
    runs = runs_in(out)
    assert len(runs) == 8
    for run_id, run in runs.items():
        attrs = run["attrs"]
        assert attrs["status"] == "ok", (run_id, attrs["message"])
        parameters = json.loads(attrs["parameters"])
        state = loop(parameters)
        assert np.array_equal(run["final_positions"], state[:, :3]), attrs["origin"]
        assert np.array_equal(run["final_velocities"], state[:, 3:]), attrs["origin"]
        assert np.abs(state[:, :3] - loop({**parameters, "frames": 0})[:, :3]).max() > 0
        if not SIMULATE:
            continue
        command = json.loads(attrs["command"])
        assert command[0] == "massspring-simulate", attrs["command"]
        trajectory = tmp_path / f"{run_id}.csv"
        done = subprocess.run([SIMULATE] + command[1:] + ["--csv", str(trajectory), "--quiet"],
                              capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stderr
        with open(trajectory, newline="") as handle:
            rows = [r for r in csv.reader(handle)][1:]
        last = str(parameters["frames"])
        cli = np.array([[float(v) for v in r[2:]] for r in rows if r[0] == last])
        assert np.array_equal(run["final_positions"], cli[:, :3]), attrs["origin"]
        assert np.array_equal(run["final_velocities"], cli[:, 3:]), attrs["origin"]


def test_a_rerun_on_the_finished_file_runs_nothing(finished):
    spec, out, _ = finished
    before = runs_in(out)
    done = subprocess.run([sys.executable, "-m", "massspring.sweep", spec, "--out", out,
                           "--scheduler", "tcp://127.0.0.1:1"],  # never contacted
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "nothing to run: the 8 runs are in" in done.stdout
    after = runs_in(out)
    assert after.keys() == before.keys()
    for k in before:
        assert after[k]["attrs"]["wall_seconds"] == before[k]["attrs"]["wall_seconds"]


def test_a_killed_worker_still_gives_all_runs(finished, tmp_path):
    _, reference, _ = finished
    spec = write_spec(str(tmp_path))
    out = str(tmp_path / "results.h5")
    killed = {}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        pids = client.run(os.getpid)  # {worker address: pid}

        def kill_the_other(run, result):
            """At the first result after which the worker that did not send it holds a run of
            its own (the 8 runs outnumber the 2 workers), kill that worker. Tried again at each
            result: on a loaded machine the other worker can be between runs at the first."""
            if killed:
                return
            processing = client.processing()
            for address, pid in pids.items():
                if pid != result["pid"] and processing.get(address):
                    killed.update(pid=pid, tasks=list(processing[address]))
                    os.kill(pid, signal.SIGKILL)
                    return

        summary = sweep(spec, out, scheduler=cluster.scheduler_address, progress=False,
                        on_result=kill_the_other)
    assert killed, "the other worker held no run at any result"
    assert summary["ran"] == 8 and summary["ok"] == 8, summary
    runs, want = runs_in(out), runs_in(reference)
    assert runs.keys() == want.keys()
    for k in runs:
        assert runs[k]["attrs"]["status"] == "ok"
        assert np.array_equal(runs[k]["final_positions"], want[k]["final_positions"])
    # the runs the killed worker held were done again, by another process
    redone = [k for k in runs if any(k in task for task in killed["tasks"])]
    assert redone and all(runs[k]["attrs"]["pid"] != killed["pid"] for k in redone)


def test_a_bad_value_is_refused_before_any_run(tmp_path):
    out = tmp_path / "results.h5"
    spec = write_spec(str(tmp_path), grid={"dt": [0.01, -0.5]})
    done = subprocess.run([sys.executable, "-m", "massspring.sweep", spec, "--out", str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 1
    assert "grid.dt[1]: must be > 0, got -0.5" in done.stderr, done.stderr
    assert not out.exists()
    cases = [
        ({"runs": [{"generate": "chain:8", "integrator": "rk4", "iterations": 3}]},
         'run 0 (runs[0]): "iterations" applies to integrator fast-mass-spring only'),
        ({"runs": [{"generate": "chain:8"}, {"generate": "chain:8", "dt": "fast"}]},
         'runs[1].dt: expected a number, got "fast"'),
        ({"base": {"generate": "net:4x4", "stifness": 10}},
         'base.stifness: unknown parameter "stifness"'),
        ({"runs": [{"scene": "no_such_scene.json"}]}, "run 0 (runs[0]): scene no_such_scene"),
    ]
    for spec, message in cases:
        path = tmp_path / "bad.json"
        path.write_text(json.dumps(spec))
        with pytest.raises(SpecError, match=None) as error:
            sweep(str(path), str(out), scheduler="tcp://127.0.0.1:1", progress=False)
        assert message in str(error.value) and str(path) in str(error.value)
        assert not out.exists()


def test_diverged_and_failed_runs_are_recorded_and_the_others_done(cluster, tmp_path):
    runs = [
        {"scene": "chain.json", "integrator": "symplectic-euler", "dt": 0.001, "frames": 20},
        # far past its stability limit: the energy guard stops it
        {"scene": "chain.json", "integrator": "forward-euler", "dt": 0.5, "frames": 20},
        # the scene has no collider 3: the set-up fails on the worker
        {"scene": "drape.json", "frames": 2, "colliders": [{"index": 3, "velocity": [0, 0, 1]}]},
    ]
    spec = write_spec(str(tmp_path), runs=runs, grid={})
    out = str(tmp_path / "results.h5")
    summary = sweep(spec, out, scheduler=cluster.scheduler_address, progress=False)
    assert summary["ran"] == 3 and summary["ok"] == 1, summary
    by_index = {r["attrs"]["index"]: r["attrs"] for r in runs_in(out).values()}
    assert by_index[0]["status"] == "ok"
    assert by_index[1]["status"] == "diverged"
    assert "the total energy passed the divergence limit" in by_index[1]["message"]
    assert by_index[2]["status"] == "failed"
    assert "colliders: index 3: the scene has 2 colliders" in by_index[2]["message"]
    # --redo-failed runs the two again, and only them
    again = sweep(spec, out, scheduler=cluster.scheduler_address, progress=False,
                  redo_failed=True)
    assert again["ran"] == 2 and again["skipped"] == 1


def test_a_generator_function_brings_its_own_force_terms():
    """{"function": ...} scenes get no default gravity: the orbit stays the orbit."""
    from massspring.sweep import run_one
    from massspring.sweep.generators import pareto

    generate = {"function": "massspring.sweep.generators:pareto", "arguments": {"scene": "orbit"}}
    result = run_one({"generate": generate, "integrator": "rk4", "dt": 0.05, "frames": 20,
                      "guard_growth": 0})
    assert result["status"] == "ok", result["message"]
    system, solver = pareto("orbit"), ms.RK4()
    solver.precompute(system, 0.05)
    for _ in range(20):
        assert solver.step(system).ok()
    assert np.array_equal(result["final_positions"], system.positions)
    assert abs(np.linalg.norm(system.positions[1]) - 1) < 1e-6  # still on its circle


def test_min_time_repeats_a_short_run_and_keeps_its_first_trajectory(tmp_path):
    """`min_time`: an ok run is repeated (timed only) until its loops add up to it; the stored
    trajectory and statistics are the first loop's, loop_seconds holds every loop's time."""
    from massspring.sweep import run_one
    from massspring.sweep.spec import load
    from massspring.sweep.store import Store

    base = {"generate": "chain:8", "integrator": "symplectic-euler", "dt": 0.001, "frames": 20}
    once = run_one(base)
    repeated = run_one({**base, "min_time": 0.02})
    assert once["status"] == repeated["status"] == "ok"
    assert once["loop_seconds"].shape == (1,)
    assert once["loop_seconds"][0] == np.sum(once["steps"]["time"])
    loops = repeated["loop_seconds"]
    assert len(loops) > 1 and np.sum(loops) >= 0.02 and np.all(loops > 0)
    assert loops[0] == np.sum(repeated["steps"]["time"])
    assert repeated["steps"]["time"].shape == (20,)
    assert np.array_equal(once["final_positions"], repeated["final_positions"])
    assert np.array_equal(once["final_velocities"], repeated["final_velocities"])
    # a diverged run is not repeated
    diverged = run_one({**base, "integrator": "forward-euler", "dt": 0.5, "min_time": 10})
    assert diverged["status"] == "diverged" and diverged["loop_seconds"].shape == (1,)
    # the file keeps each loop's time
    spec = write_spec(str(tmp_path), runs=[{**base, "min_time": 0.02}], grid={})
    run = load(spec)[1][0]
    with Store(str(tmp_path / "results.h5")) as store:
        store.write(run, repeated)
    with h5py.File(tmp_path / "results.h5", "r") as f:
        assert np.array_equal(f["runs"][run.id]["loop_seconds"][()], loops)


def long_runs(folder, count, frames):
    """A spec of `count` runs of a 20 x 20 cloth, each some tenths of a second to seconds."""
    runs = [{"generate": "cloth:20x20", "iterations": 10, "frames": frames + k}
            for k in range(count)]
    return write_spec(folder, runs=runs, grid={})


@pytest.mark.parametrize("verbose", [False, True])
def test_dask_output_stays_off_stderr_when_a_worker_is_killed(tmp_path, capfd, caplog, verbose):
    """The sweep's own local cluster (2 workers); the worker that sent the first result is killed.
    Dask's nanny in this process logs `distributed.nanny - WARNING - Restarting worker` (a log
    record, seen by caplog: pytest holds the stream Dask's handler writes to), and the worker
    processes write to the file descriptor 2 they inherit (seen by capfd): both with verbose
    only."""
    spec = long_runs(str(tmp_path), 4, 400)
    out = str(tmp_path / "results.h5")
    distributed_level = logging.getLogger("distributed").level
    client_level = logging.getLogger("distributed.client").level
    environment = os.environ.get("DASK_LOGGING__DISTRIBUTED")
    killed = []

    def kill_the_sender(run, result):
        if not killed:
            killed.append(result["pid"])
            os.kill(result["pid"], signal.SIGKILL)

    capfd.readouterr()
    caplog.clear()
    summary = sweep(spec, out, workers=2, progress=False, on_result=kill_the_sender,
                    verbose=verbose)
    err = capfd.readouterr().err
    assert killed and summary["ran"] == 4 and summary["ok"] == 4, summary
    dask_records = [f"{r.name} - {r.levelname} - {r.getMessage()}" for r in caplog.records
                    if r.name.startswith("distributed") and r.levelno >= logging.WARNING]
    if verbose:
        assert "distributed.nanny - WARNING - Restarting worker" in dask_records, dask_records
    else:
        assert not dask_records, dask_records
        assert "distributed." not in err and "Traceback" not in err, err
    # the caller's logging set-up and environment, as they were
    assert logging.getLogger("distributed").level == distributed_level
    assert logging.getLogger("distributed.client").level == client_level
    assert os.environ.get("DASK_LOGGING__DISTRIBUTED") == environment


def test_ctrl_c_prints_the_sweeps_own_words_only(tmp_path):
    """Ctrl-C in a terminal interrupts the whole process group, the workers too: the command
    exits 130 with its progress and its own message, and no Dask log line or worker traceback."""
    spec = long_runs(str(tmp_path), 6, 1500)
    out = str(tmp_path / "results.h5")
    command = subprocess.Popen([sys.executable, "-m", "massspring.sweep", spec, "--out", out,
                                "--workers", "2"], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        lines = []
        for line in command.stderr:  # the progress bar's first line: a run is committed
            lines.append(line)
            if " 1/6 runs" in line:
                break
        os.killpg(command.pid, signal.SIGINT)
        stdout, rest = command.communicate(timeout=300)
    finally:
        if command.poll() is None:
            os.killpg(command.pid, signal.SIGKILL)
            command.wait()
    stderr = "".join(lines) + rest
    assert command.returncode == 130, stderr
    assert "massspring.sweep: interrupted; the runs committed so far are in" in stderr
    foreign = [line for line in stderr.splitlines()
               if line and not line.startswith(("[", "massspring.sweep: "))]
    assert not foreign, stderr
