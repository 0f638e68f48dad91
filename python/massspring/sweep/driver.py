"""Runs a sweep on a Dask cluster and commits each run to the HDF5 file as it finishes.

The client (this process) checks the whole spec first, skips the runs the file already holds,
submits one task per run (a scene file's bytes inside it: workers need not share the client's
files), and writes each result as it arrives (store.py). A worker that dies takes its tasks with
it; the scheduler gives them to another worker (Dask's distributed.scheduler.allowed-failures, 3
by default, bounds how often one task may do that). A task the cluster loses all the same (past
that bound, or a result lost with its worker before it was fetched) is submitted again, twice at
most; then the run is recorded as failed with Dask's message. A run that raises or diverges is
recorded with its message and the others go on."""

import contextlib
import importlib
import json
import os
import uuid

import massspring as ms

from . import runner, spec as specs
from .progress import Progress
from .quiet import dask_logs_silenced

# The workers' preload that keeps their stderr off the terminal (quiet.py).
quiet_module = __name__.rpartition(".")[0] + ".quiet"

# Parameters massspring-simulate has an option for (the option is --NAME with dashes).
_CLI_OPTIONS = {
    "integrator", "dt", "frames", "every", "guard_growth", "self_collision", "shrink",
    "contact_weight", "iterations",
    "tolerance", "pins", "penalty_weight", "acceleration", "chebyshev_rho", "chebyshev_gamma",
    "chebyshev_delay", "chebyshev_estimate_iterations", "anderson_window", "threads",
    "ordering", "initial_guess", "newton_iterations", "newton_tolerance", "line_search",
    "gravity", "force"}
# Parameters that change nothing massspring-simulate computes.
_NOT_COMPUTED = {"name", "save_frames", "energy", "min_time"}


def command_line(run):
    """The massspring-simulate arguments that run the same (its --csv then holds the same
    trajectory, bit for bit), or None when the run has something the tool has no option for."""
    p = run.parameters
    if p.get("integrator") == "rk4" or isinstance(p.get("generate", ""), dict):
        return None
    if any(k not in _CLI_OPTIONS | _NOT_COMPUTED | {"scene", "generate"} for k in p):
        return None
    args = [run.scene_path] if "scene" in p else ["--generate", p["generate"]]
    args += ["--frames", str(run.get("frames")), "--guard-growth", repr(run.get("guard_growth"))]
    for key, value in p.items():
        if key not in _CLI_OPTIONS or key in ("frames", "guard_growth"):
            continue
        if isinstance(value, bool):
            value = "on" if value else "off"
        elif isinstance(value, list):
            value = ",".join(repr(v) for v in value)
        args += ["--" + key.replace("_", "-"), value if isinstance(value, str) else repr(value)]
    return args


class _Scenes:
    """Each scene file loaded once on the client: checked, its own integrator known, its files
    bundled for the workers."""

    def __init__(self):
        self.loaded = {}

    def get(self, run):
        path = run.scene_path
        if path not in self.loaded:
            try:
                loaded = ms.load_scene_file(path)
            except (ms.Error, OSError) as e:
                raise specs.SpecError(f"{run.where()}: scene {run.parameters['scene']}: {e}") \
                    from None
            self.loaded[path] = (loaded, runner.scene_bundle(path, list(loaded.files) or [path]))
        return self.loaded[path]

    def integrator_of(self, run):
        if run.scene_path is None:
            return None
        loaded = self.get(run)[0]
        if loaded.fosssim is None:
            return None
        return specs.FOSSSIM_INTEGRATORS.get(loaded.fosssim.integrator)


def check(spec_path):
    """The runs of a spec file, every scene loaded once; raises SpecError naming the entry."""
    scenes = _Scenes()
    _, runs = specs.load(spec_path, integrator_of_scene=scenes.integrator_of)
    for run in runs:
        generator = run.parameters.get("generate")
        if isinstance(generator, dict):
            module, _, name = generator["function"].partition(":")
            try:
                found = callable(getattr(importlib.import_module(module), name, None))
            except ImportError as e:
                raise specs.SpecError(f"{spec_path}: {run.where()}: generate: cannot import "
                                      f"{module}: {e}") from None
            if not found:
                raise specs.SpecError(f"{spec_path}: {run.where()}: generate: {module} has no "
                                      f"function {name}")
    return runs, scenes


def sweep(spec_path, out, scheduler=None, workers=None, client=None, redo_failed=False,
          retries=1, progress=True, on_result=None, verbose=False):
    """Runs the sweep of the spec file `spec_path` into the HDF5 file `out`.

    @param scheduler    an existing Dask scheduler's address (tcp://HOST:8786), used as it is;
                        None: a LocalCluster of `workers` processes (default: os.cpu_count()),
                        one thread each, closed at the end
    @param client       a dask.distributed.Client to use instead (left open)
    @param redo_failed  run again the runs the file records as failed, diverged or skipped
    @param retries      Dask's retries of a task that raised (a run itself never raises)
    @param on_result    called as on_result(run, result) after each run is committed
    @param verbose      also show Dask's own log lines (Dask's default: its warnings and errors)
                        and the local cluster's workers' stderr; otherwise only the sweep's
                        messages are printed (quiet.py), the logging set-up restored afterwards
    @return {"runs": total, "skipped": already in the file, "ran": ..., "ok", "not_ok"}"""
    from .store import Store  # noqa: PLC0415: h5py, needed here only

    runs, scenes = check(spec_path)
    with open(spec_path) as handle:
        spec_text = handle.read()
    summary = {"runs": len(runs), "skipped": 0, "ran": 0, "ok": 0, "not_ok": 0}
    with Store(out, spec_text, ms.__version__) as store:
        todo = []
        for run in runs:
            status = store.status(run.id)
            if status is None or (redo_failed and status != "ok"):
                todo.append(run)
            else:
                summary["skipped"] += 1
        if not todo:
            if progress:
                print(f"massspring.sweep: nothing to run: the {len(runs)} runs are in {out}",
                      flush=True)
            return summary
        if progress:
            print(f"massspring.sweep: {len(todo)} runs to do ({summary['skipped']} already in "
                  f"{out})", flush=True)

        from dask.distributed import Client, LocalCluster, as_completed  # noqa: PLC0415

        # Dask's own output silenced (quiet.py) until the cluster is closed, unless verbose
        with contextlib.nullcontext() if verbose else dask_logs_silenced():
            cluster = own_client = None
            try:
                if client is None:
                    if scheduler:
                        own_client = client = Client(scheduler)
                    else:
                        # No dashboard; the scheduler's HTTP server (Dask's health and
                        # metrics routes) on a free port, not 8787: two sweeps at once on one
                        # machine would otherwise collide there (and Dask warn about it).
                        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1,
                                               threads_per_worker=1, processes=True,
                                               dashboard_address=None,
                                               scheduler_kwargs={"dashboard_address": ":0"},
                                               preload=[] if verbose else [quiet_module])
                        own_client = client = Client(cluster)

                def submit(run):
                    # The scene's bytes travel inside the task, so they live as long as the task
                    # does (scattered data dies with the worker holding it, and its tasks with it).
                    bundle = scenes.get(run)[1] if run.scene_path is not None else None
                    future = client.submit(runner.run, run.parameters, bundle, pure=False,
                                           retries=retries,
                                           key=f"massspring-{run.id}-{uuid.uuid4().hex[:8]}")
                    futures[future.key] = (future, run)
                    return future

                futures, attempts = {}, {}
                pending = as_completed([submit(run) for run in todo])
                bar = Progress(len(todo), enabled=progress)
                for future in pending:
                    run = futures.pop(future.key)[1]
                    try:
                        result = future.result()
                    except Exception as e:  # noqa: BLE001: a lost task is recorded, not raised
                        # runner.run never raises: the cluster lost the task (its workers died more
                        # often than allowed-failures, or it was cancelled). Submitted again, twice
                        # at most.
                        attempts[run.id] = attempts.get(run.id, 0) + 1
                        if attempts[run.id] <= 2:
                            future.release()
                            pending.add(submit(run))
                            continue
                        result = {"status": "failed",
                                  "message": f"the cluster could not run it: {type(e).__name__}: {e}"}
                    future.release()
                    args = command_line(run)
                    store.write(run, result, json.dumps(["massspring-simulate"] + args)
                                if args else "")
                    ok = result["status"] == "ok"
                    summary["ran"] += 1
                    summary["ok" if ok else "not_ok"] += 1
                    bar.advance(ok)
                    if on_result is not None:
                        on_result(run, result)
            finally:
                if own_client is not None:
                    own_client.close()
                if cluster is not None:
                    cluster.close()
    if progress:
        print(f"massspring.sweep: {summary['ran']} runs done ({summary['ok']} ok, "
              f"{summary['not_ok']} not: see their \"message\"), {summary['skipped']} were in "
              f"the file; results in {out}", flush=True)
    return summary
